#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "host/runtime/KernelSources.hpp"
#include "host/runtime/opencl.hpp"
#include "kernels/shared_types.h"
#include "tests/support/TestDevice.hpp"

namespace {

// Every struct of kernels/shared_types.h and every field of it. The same list produces the host values
// (sizeof, offsetof) and the OpenCL C that measures them on the device.
#define FW_SHARED_STRUCTS(X) \
  X(FwGrid);                 \
  X(FwLevel);                \
  X(FwStep);                 \
  X(FwGust);                 \
  X(FwTke)
#define FW_SHARED_FIELDS(X)      \
  X(FwGrid, nx);                 \
  X(FwGrid, ny);                 \
  X(FwGrid, nz);                 \
  X(FwGrid, bc);                 \
  X(FwGrid, h);                  \
  X(FwGrid, origin);             \
  X(FwGrid, ox);                 \
  X(FwGrid, oy);                 \
  X(FwGrid, wrap);               \
  X(FwGrid, domain);             \
  X(FwLevel, nx);                \
  X(FwLevel, ny);                \
  X(FwLevel, nz);                \
  X(FwLevel, periodic);          \
  X(FwLevel, ox);                \
  X(FwLevel, oy);                \
  X(FwStep, dt);                 \
  X(FwStep, time);               \
  X(FwStep, ambient);            \
  X(FwStep, turbulence_sigma);   \
  X(FwStep, turbulence_offset);  \
  X(FwStep, turbulence_cells);   \
  X(FwStep, turbulence_spacing); \
  X(FwGust, start);              \
  X(FwGust, duration);           \
  X(FwGust, peak_speed);         \
  X(FwGust, radius);             \
  X(FwGust, center);             \
  X(FwGust, travel);             \
  X(FwGust, direction);          \
  X(FwTke, viscosity_length);    \
  X(FwTke, dissipation_rate);    \
  X(FwTke, canopy_sink);         \
  X(FwTke, wake_fraction);       \
  X(FwTke, floor);               \
  X(FwTke, inflow)
// The trees' structs (packed by trees/Forest.hpp), kept in their own lists.
#define FW_TREE_STRUCTS(X) \
  X(FwSpecies);            \
  X(FwTreeInstance);       \
  X(FwBranch);             \
  X(FwBranchSpecies);      \
  X(FwBranchTree)
#define FW_TREE_FIELDS(X)             \
  X(FwSpecies, node_count);           \
  X(FwSpecies, mode_count);           \
  X(FwSpecies, sample_count);         \
  X(FwSpecies, shape_offset);         \
  X(FwSpecies, projection_offset);    \
  X(FwSpecies, sample_point_offset);  \
  X(FwSpecies, modal_offset);         \
  X(FwSpecies, skeleton_offset);      \
  X(FwTreeInstance, species);         \
  X(FwTreeInstance, mode_offset);     \
  X(FwTreeInstance, node_offset);     \
  X(FwTreeInstance, sample_offset);   \
  X(FwTreeInstance, position);        \
  X(FwTreeInstance, cos_yaw);         \
  X(FwTreeInstance, sin_yaw);         \
  X(FwTreeInstance, scale);           \
  X(FwBranch, node);                  \
  X(FwBranch, parent_node);           \
  X(FwBranch, parent_entry);          \
  X(FwBranch, rest);                  \
  X(FwBranch, centre);                \
  X(FwBranch, length);                \
  X(FwBranch, mass);                  \
  X(FwBranch, axial_inertia);         \
  X(FwBranch, stiffness);             \
  X(FwBranch, branch_drag);           \
  X(FwBranch, leaf_drag);             \
  X(FwBranch, spring);                \
  X(FwBranchSpecies, model);          \
  X(FwBranchSpecies, normal_drag);    \
  X(FwBranchSpecies, damping);        \
  X(FwBranchSpecies, max_angle);      \
  X(FwBranchSpecies, sway_amplitude); \
  X(FwBranchSpecies, sway_omega);     \
  X(FwBranchTree, instance);          \
  X(FwBranchTree, entry_offset);      \
  X(FwBranchTree, id)
// The damage structs (packed by host/stages/DamageStages).
#define FW_DAMAGE_STRUCTS(X) \
  X(FwStem);                 \
  X(FwStemAxis);             \
  X(FwTreeDamage);           \
  X(FwFall)
#define FW_DAMAGE_FIELDS(X)         \
  X(FwStem, section_count);         \
  X(FwStem, block_count);           \
  X(FwStem, map_offset);            \
  X(FwStem, section_offset);        \
  X(FwStem, axis_offset);           \
  X(FwStemAxis, axis);              \
  X(FwStemAxis, entry);             \
  X(FwTreeDamage, state);           \
  X(FwTreeDamage, failed_section);  \
  X(FwTreeDamage, time);            \
  X(FwTreeDamage, break_height);    \
  X(FwTreeDamage, top_wind);        \
  X(FwTreeDamage, max_utilisation); \
  X(FwTreeDamage, max_base_moment); \
  X(FwTreeDamage, utilisation);     \
  X(FwFall, instance);              \
  X(FwFall, pivot);                 \
  X(FwFall, cos_angle);             \
  X(FwFall, sin_angle);             \
  X(FwFall, direction);             \
  X(FwFall, drop)
// The leaves' structs (packed by host/stages/LeafStages).
#define FW_LEAF_STRUCTS(X) X(FwLeafSpecies)
#define FW_LEAF_FIELDS(X)            \
  X(FwLeafSpecies, model);           \
  X(FwLeafSpecies, leaf_offset);     \
  X(FwLeafSpecies, leaf_count);      \
  X(FwLeafSpecies, side);            \
  X(FwLeafSpecies, lever);           \
  X(FwLeafSpecies, area);            \
  X(FwLeafSpecies, mass);            \
  X(FwLeafSpecies, omega);           \
  X(FwLeafSpecies, damping_ratio);   \
  X(FwLeafSpecies, amplitude);       \
  X(FwLeafSpecies, roll_coupling);   \
  X(FwLeafSpecies, reference_speed); \
  X(FwLeafSpecies, flight_drag)

struct LayoutEntry {
  std::string what;    // "sizeof(FwGrid)" or "offsetof(FwGrid, bc)"
  unsigned value;      // bytes, on the host
  std::string device;  // OpenCL C expression of the same quantity
};

std::vector<LayoutEntry> host_layout() {
  std::vector<LayoutEntry> entries;
#define FW_SIZE_ENTRY(T) entries.push_back({"sizeof(" #T ")", unsigned(sizeof(T)), "(uint)sizeof(" #T ")"})
#define FW_OFFSET_ENTRY(T, f)                                              \
  entries.push_back({"offsetof(" #T ", " #f ")", unsigned(offsetof(T, f)), \
                     "(uint)((__private char*)&v_" #T "." #f " - (__private char*)&v_" #T ")"})
  FW_SHARED_STRUCTS(FW_SIZE_ENTRY);
  FW_SHARED_FIELDS(FW_OFFSET_ENTRY);
  FW_TREE_STRUCTS(FW_SIZE_ENTRY);
  FW_TREE_FIELDS(FW_OFFSET_ENTRY);
  FW_LEAF_STRUCTS(FW_SIZE_ENTRY);
  FW_LEAF_FIELDS(FW_OFFSET_ENTRY);
  FW_DAMAGE_STRUCTS(FW_SIZE_ENTRY);
  FW_DAMAGE_FIELDS(FW_OFFSET_ENTRY);
#undef FW_SIZE_ENTRY
#undef FW_OFFSET_ENTRY
  return entries;
}

// The header's text followed by a kernel that writes every entry's device value into out[].
std::string layout_kernel_source(const std::vector<LayoutEntry>& entries) {
  std::string source = fw::host::kernel_source("shared_types.h");
  source += "\n#line 1 \"shared_types_test_kernel\"\n";
  source += "kernel void shared_types_layout(global uint* out) {\n";
#define FW_PRIVATE_INSTANCE(T) source += "  " #T " v_" #T ";\n"
  FW_SHARED_STRUCTS(FW_PRIVATE_INSTANCE);
  FW_TREE_STRUCTS(FW_PRIVATE_INSTANCE);
  FW_LEAF_STRUCTS(FW_PRIVATE_INSTANCE);
  FW_DAMAGE_STRUCTS(FW_PRIVATE_INSTANCE);
#undef FW_PRIVATE_INSTANCE
  for (std::size_t n = 0; n < entries.size(); ++n)
    source += fmt::format("  out[{}] = {};\n", n, entries[n].device);
  source += "}\n";
  return source;
}

}  // namespace

TEST_CASE("shared_types: host structs are packed 32-bit fields without padding") {
  // Field counts: FwGrid 3 + 6 + 1 + 3 + 2 + 2 + 2, FwLevel 6, FwStep 2 + 3 + 1 + 3 + 3 + 1, FwGust 4 + 3 *
  // 3, FwTke 2 + 2 + 4.
  CHECK(sizeof(FwGrid) == 19 * 4);
  CHECK(sizeof(FwLevel) == 6 * 4);
  CHECK(sizeof(FwStep) == 13 * 4);
  CHECK(sizeof(FwGust) == 13 * 4);
  CHECK(sizeof(FwTke) == 8 * 4);
  CHECK(alignof(FwGrid) == 4);
  CHECK(alignof(FwGust) == 4);
  CHECK(offsetof(FwGrid, bc) == 12);
  CHECK(offsetof(FwGrid, h) == 36);
  CHECK(offsetof(FwGrid, origin) == 40);
  CHECK(offsetof(FwGust, direction) == 40);
}

TEST_CASE("shared_types: tree structs are packed 32-bit fields without padding", "[forest]") {
  // FwSpecies 8 ints; FwTreeInstance 4 ints + 3 floats of position + cos, sin, scale.
  CHECK(sizeof(FwSpecies) == 8 * 4);
  CHECK(sizeof(FwTreeInstance) == 10 * 4);
  // FwLeafSpecies 3 ints + 9 floats + 3 amplitudes.
  CHECK(sizeof(FwLeafSpecies) == 15 * 4);
  CHECK(alignof(FwSpecies) == 4);
  CHECK(alignof(FwTreeInstance) == 4);
  CHECK(offsetof(FwSpecies, modal_offset) == 24);
  CHECK(offsetof(FwSpecies, skeleton_offset) == 28);
  CHECK(offsetof(FwTreeInstance, position) == 16);
  CHECK(offsetof(FwTreeInstance, cos_yaw) == 28);
  CHECK(offsetof(FwTreeInstance, scale) == 36);
  // FwStem 5 ints; FwStemAxis 3 floats + an int; FwTreeDamage 2 ints + 2 floats + 3 of wind + 3 floats.
  CHECK(sizeof(FwStem) == 5 * 4);
  CHECK(sizeof(FwStemAxis) == 4 * 4);
  CHECK(sizeof(FwTreeDamage) == 10 * 4);
  CHECK(offsetof(FwTreeDamage, top_wind) == 16);
}

TEST_CASE("shared_types: the rest-leaf table's fields take one row each, vectors three, none overlapping",
          "[forest]") {
  // In the order of shared_types.h: 6 vectors, the 3 phases and 3 frequencies, then 4 scalars.
  const int rows[] = {FW_REST_ANCHOR,       FW_REST_PETIOLE,     FW_REST_HINGE, FW_REST_NORMAL,
                      FW_REST_SWING,        FW_REST_TUMBLE_AXIS, FW_REST_PHASE, FW_REST_FREQUENCY,
                      FW_REST_HINGE_NORMAL, FW_REST_KAPPA,       FW_REST_ALONG, FW_REST_STRENGTH,
                      FW_REST_FIELDS};
  const int width[] = {3, 3, 3, 3, 3, 3, 3, 3, 1, 1, 1, 1};
  CHECK(rows[0] == 0);
  for (int f = 0; f < 12; ++f) CHECK(rows[f + 1] == rows[f] + width[f]);
}

TEST_CASE("shared_types: OpenCL C and the host agree on sizeof and offsetof of every struct and field") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  const auto entries = host_layout();
  // Shared structs and fields (FwTke's 1 and 6 among them), the trees' (the element models' 3 structs and
  // 21 fields among them), the leaves' (1 struct, 13 fields), the damage's (4 structs, 21 fields).
  REQUIRE(entries.size() == 5 + 36 + 5 + 37 + 1 + 13 + 4 + 21);
  const std::string source = layout_kernel_source(entries);
  INFO(source);

  const cl::Program program = cc->build_source("shared_types_layout.cl", source);
  fw::host::Kernel kernel(program, "shared_types_layout");
  const std::size_t bytes = entries.size() * sizeof(cl_uint);
  cl::Buffer out(cc->context(), CL_MEM_WRITE_ONLY, bytes);
  // One item writes every entry: a group of one, which the range needs no rounding for.
  kernel.set_args(out).enqueue(*cc, cl::NDRange(1), cl::NDRange(1));
  std::vector<cl_uint> device(entries.size(), 0xFFFFFFFFu);
  cc->queue().enqueueReadBuffer(out, CL_TRUE, 0, bytes, device.data());

  for (std::size_t n = 0; n < entries.size(); ++n) {
    INFO(entries[n].what << ": host " << entries[n].value << ", device " << device[n]);
    CHECK(device[n] == entries[n].value);
  }
}
