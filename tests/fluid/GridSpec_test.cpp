#include "fluid/GridSpec.hpp"

#include <catch2/catch.hpp>

#include <limits>
#include <stdexcept>
#include <string>

using fw::fluid::BoundaryType;
using fw::fluid::GridSpec;

namespace {

GridSpec grid(int nx, int ny, int nz, double h_m) {
  GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = h_m;
  return spec;
}

// The message of the std::invalid_argument that validate() throws, or "" when the spec is valid.
std::string validation_error(const GridSpec& spec) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

void set_axis(GridSpec& spec, int axis, BoundaryType lo, BoundaryType hi) {
  spec.boundary[2 * axis] = lo;
  spec.boundary[2 * axis + 1] = hi;
}

}  // namespace

TEST_CASE("GridSpec: a positive grid with matching boundaries validates") {
  GridSpec spec = grid(8, 6, 4, 0.5);
  CHECK_NOTHROW(spec.validate());
  set_axis(spec, 0, BoundaryType::inflow, BoundaryType::outflow);
  set_axis(spec, 1, BoundaryType::periodic, BoundaryType::periodic);
  spec.boundary[FW_FACE_GROUND] = BoundaryType::no_slip;
  CHECK_NOTHROW(spec.validate());
  // A single cell along a periodic axis is allowed (it couples to itself).
  GridSpec flat = grid(8, 8, 1, 1.0);
  set_axis(flat, 2, BoundaryType::periodic, BoundaryType::periodic);
  CHECK_NOTHROW(flat.validate());
}

TEST_CASE("GridSpec: zero or negative dimensions are rejected with a 'GridSpec:' message") {
  for (const GridSpec& spec : {grid(0, 4, 4, 1.0), grid(4, 0, 4, 1.0), grid(4, 4, 0, 1.0),
                               grid(-2, 4, 4, 1.0), grid(4, -1, 4, 1.0), grid(4, 4, -8, 1.0)}) {
    INFO(spec.nx << " x " << spec.ny << " x " << spec.nz);
    CHECK_THROWS_AS(spec.validate(), std::invalid_argument);
    CHECK_THAT(validation_error(spec), Catch::StartsWith("GridSpec:") && Catch::Contains("dimensions"));
  }
}

TEST_CASE("GridSpec: a cell size that is not a positive finite number is rejected") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double h : {0.0, -1.0, nan, inf, -inf}) {
    INFO("h = " << h);
    const std::string message = validation_error(grid(4, 4, 4, h));
    CHECK_THAT(message, Catch::StartsWith("GridSpec:") && Catch::Contains("cell size"));
  }
}

TEST_CASE("GridSpec: a non-finite origin is rejected") {
  GridSpec spec = grid(4, 4, 4, 1.0);
  spec.origin[1] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(validation_error(spec), Catch::StartsWith("GridSpec:") && Catch::Contains("origin"));
}

TEST_CASE("GridSpec: a periodic face whose opposite face is not periodic is rejected") {
  for (int axis = 0; axis < 3; ++axis) {
    for (bool low_periodic : {true, false}) {
      GridSpec spec = grid(4, 4, 4, 1.0);
      if (low_periodic)
        set_axis(spec, axis, BoundaryType::periodic, BoundaryType::outflow);
      else
        set_axis(spec, axis, BoundaryType::slip, BoundaryType::periodic);
      const std::string periodic_face = fw::fluid::face_name(low_periodic ? 2 * axis : 2 * axis + 1);
      INFO("axis " << axis << ", periodic face " << periodic_face);
      const std::string message = validation_error(spec);
      CHECK_THAT(message, Catch::StartsWith("GridSpec:") &&
                              Catch::Contains("the " + periodic_face + " face is periodic"));
    }
  }
}

TEST_CASE("GridSpec: an odd cell count above 1 on a periodic axis is rejected") {
  for (int axis = 0; axis < 3; ++axis)
    for (int odd : {3, 5, 101}) {
      int n[3] = {4, 4, 4};
      n[axis] = odd;
      GridSpec spec = grid(n[0], n[1], n[2], 1.0);
      set_axis(spec, axis, BoundaryType::periodic, BoundaryType::periodic);
      INFO("axis " << axis << ", " << odd << " cells");
      CHECK_THAT(validation_error(spec), Catch::StartsWith("GridSpec:") && Catch::Contains("even number"));
      // The same count on a non-periodic axis is fine.
      set_axis(spec, axis, BoundaryType::inflow, BoundaryType::outflow);
      CHECK(validation_error(spec).empty());
    }
}

TEST_CASE("GridSpec: a grid whose face count exceeds 2^31 is rejected") {
  // 2048 x 1024 x 1024 cells: (nx+1)(ny+1)(nz+1) = 2.15e9 > 2^31 - 1.
  CHECK_THAT(validation_error(grid(2048, 1024, 1024, 1.0)),
             Catch::StartsWith("GridSpec:") && Catch::Contains("2^31"));
  // A long thin grid trips it too.
  CHECK_THAT(validation_error(grid(1 << 30, 2, 1, 1.0)), Catch::StartsWith("GridSpec:"));
  // The largest int along one axis: nx + 1 must not overflow on the way to the check.
  const int most = std::numeric_limits<int>::max();
  CHECK_THAT(validation_error(grid(most, 1, 1, 1.0)),
             Catch::StartsWith("GridSpec:") && Catch::Contains("2^31"));
  CHECK_THAT(validation_error(grid(1, most, 1, 1.0)),
             Catch::StartsWith("GridSpec:") && Catch::Contains("2^31"));
  CHECK_THAT(validation_error(grid(1, 1, most, 1.0)),
             Catch::StartsWith("GridSpec:") && Catch::Contains("2^31"));
  // 1023 x 1023 x 1023 cells: 1024^3 = 2^30 faces, well inside the range.
  CHECK(validation_error(grid(1023, 1023, 1023, 1.0)).empty());
}

TEST_CASE("GridSpec: an out-of-range boundary value is rejected naming the face") {
  GridSpec spec = grid(4, 4, 4, 1.0);
  spec.boundary[FW_FACE_NORTH] = static_cast<BoundaryType>(7);
  CHECK_THAT(validation_error(spec), Catch::StartsWith("GridSpec:") && Catch::Contains("north"));
}

TEST_CASE("GridSpec: to_string names the five boundary types, whose values are the kernels' FW_BC_*") {
  CHECK(fw::fluid::to_string(BoundaryType::inflow) == "inflow");
  CHECK(fw::fluid::to_string(BoundaryType::outflow) == "outflow");
  CHECK(fw::fluid::to_string(BoundaryType::slip) == "slip");
  CHECK(fw::fluid::to_string(BoundaryType::no_slip) == "no_slip");
  CHECK(fw::fluid::to_string(BoundaryType::periodic) == "periodic");
  CHECK(static_cast<int>(BoundaryType::inflow) == FW_BC_INFLOW);
  CHECK(static_cast<int>(BoundaryType::periodic) == FW_BC_PERIODIC);
}

TEST_CASE("GridSpec: face_name names the six faces in FW_FACE_* order") {
  CHECK(fw::fluid::face_name(FW_FACE_WEST) == "west");
  CHECK(fw::fluid::face_name(FW_FACE_EAST) == "east");
  CHECK(fw::fluid::face_name(FW_FACE_SOUTH) == "south");
  CHECK(fw::fluid::face_name(FW_FACE_NORTH) == "north");
  CHECK(fw::fluid::face_name(FW_FACE_GROUND) == "ground");
  CHECK(fw::fluid::face_name(FW_FACE_TOP) == "top");
}

TEST_CASE("GridSpec: cell and face counts follow the MAC layout") {
  const GridSpec spec = grid(5, 3, 2, 1.0);
  CHECK(spec.cell_count() == 30);
  CHECK(spec.u_count() == 6 * 3 * 2);
  CHECK(spec.v_count() == 5 * 4 * 2);
  CHECK(spec.w_count() == 5 * 3 * 3);
}

TEST_CASE("GridSpec: has_dirichlet_pressure is true exactly when some face is outflow") {
  GridSpec spec = grid(4, 4, 4, 1.0);
  CHECK_FALSE(spec.has_dirichlet_pressure());
  spec.boundary[FW_FACE_WEST] = BoundaryType::inflow;
  spec.boundary[FW_FACE_GROUND] = BoundaryType::no_slip;
  set_axis(spec, 1, BoundaryType::periodic, BoundaryType::periodic);
  CHECK_FALSE(spec.has_dirichlet_pressure());
  for (int f = 0; f < 6; ++f) {
    GridSpec one = grid(4, 4, 4, 1.0);
    one.boundary[f] = BoundaryType::outflow;
    INFO("outflow on the " << fw::fluid::face_name(f) << " face");
    CHECK(one.has_dirichlet_pressure());
  }
}

TEST_CASE("GridSpec: periodic(axis) reads the axis' low face") {
  GridSpec spec = grid(4, 4, 4, 1.0);
  set_axis(spec, 1, BoundaryType::periodic, BoundaryType::periodic);
  CHECK_FALSE(spec.periodic(0));
  CHECK(spec.periodic(1));
  CHECK_FALSE(spec.periodic(2));
}

TEST_CASE("GridSpec: to_device copies dimensions, boundaries, cell size and origin") {
  GridSpec spec = grid(16, 8, 4, 0.25);
  spec.origin = {-10.0, 20.5, 3.0};
  spec.boundary = {BoundaryType::inflow,   BoundaryType::outflow, BoundaryType::periodic,
                   BoundaryType::periodic, BoundaryType::no_slip, BoundaryType::slip};
  const FwGrid g = spec.to_device();
  CHECK(g.nx == 16);
  CHECK(g.ny == 8);
  CHECK(g.nz == 4);
  CHECK(g.bc[FW_FACE_WEST] == FW_BC_INFLOW);
  CHECK(g.bc[FW_FACE_EAST] == FW_BC_OUTFLOW);
  CHECK(g.bc[FW_FACE_SOUTH] == FW_BC_PERIODIC);
  CHECK(g.bc[FW_FACE_NORTH] == FW_BC_PERIODIC);
  CHECK(g.bc[FW_FACE_GROUND] == FW_BC_NO_SLIP);
  CHECK(g.bc[FW_FACE_TOP] == FW_BC_SLIP);
  // Exact: all values are representable in float.
  CHECK(g.h == 0.25f);
  CHECK(g.origin[0] == -10.0f);
  CHECK(g.origin[1] == 20.5f);
  CHECK(g.origin[2] == 3.0f);
}
