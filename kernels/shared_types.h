/* Plain structs and constants shared by the host (C++) and the kernels (OpenCL C 1.2).
 *
 * Every struct holds only 32-bit scalars and fixed arrays of them, so C++ and OpenCL C lay them out
 * identically; tests/kernels/shared_types_test.cpp checks sizeof and offsetof on both sides.
 * No float3/float4 here: their alignment differs between the two languages.
 */
#ifndef FORESTWIND_SHARED_TYPES_H
#define FORESTWIND_SHARED_TYPES_H

#ifdef __OPENCL_VERSION__
typedef int fw_int;
typedef uint fw_uint;
#else
#include <cstdint>
typedef std::int32_t fw_int;
typedef std::uint32_t fw_uint;
#endif

/* Values per work-item in the lane kernels (kernels/lanes.cl: vector arithmetic of FW_LANES floats). */
#define FW_LANES 16

/* Windowed loads (kernels/lanes.cl) blend contiguous loads at up to FW_WINDOW_SHIFTS shifts, and so read up
 * to FW_WINDOW_SLACK values past the last one a lane needs: buffers read that way carry that many more. */
#define FW_WINDOW_SHIFTS 3
#define FW_WINDOW_SLACK (FW_WINDOW_SHIFTS - 1)

/* Boundary condition of one domain face. */
#define FW_BC_INFLOW 0   /* velocity prescribed by the ambient wind profile */
#define FW_BC_OUTFLOW 1  /* open: pressure 0 in the ghost cell, zero-gradient velocity */
#define FW_BC_SLIP 2     /* free-slip wall: no normal flow, zero tangential stress */
#define FW_BC_NO_SLIP 3  /* wall: no normal flow, zero tangential velocity */
#define FW_BC_PERIODIC 4 /* wraps to the opposite face; both faces of the axis must be periodic */

/* Domain faces, in the order of FwGrid.bc. */
#define FW_FACE_WEST 0   /* -x */
#define FW_FACE_EAST 1   /* +x */
#define FW_FACE_SOUTH 2  /* -y */
#define FW_FACE_NORTH 3  /* +y */
#define FW_FACE_GROUND 4 /* -z */
#define FW_FACE_TOP 5    /* +z */

/* Per-cell pressure mask (one byte a cell). Bit f (f = face index above) is set when the cell's face f is
 * "open" for the pressure equation: it couples to a fluid neighbour (or, through a periodic boundary, to
 * the cell on the other side) or to a Dirichlet ghost p = 0 (outflow). Closed faces (walls, inflow, solids)
 * carry a prescribed velocity and do not appear in the Poisson operator. */
#define FW_MASK_OPEN_ALL 63
#define FW_MASK_FLUID 64

/* The colour argument of the pressure kernels that start a smoothing from a zero guess for a Jacobi
 * smoother, whose sweep updates every cell (a red-black pass passes its colour, 0 or 1). */
#define FW_SMOOTH_ALL_CELLS (-1)

/* The plane statistics' terms (kernels/plane_statistics.cl, host/stages/PlaneStatistics.hpp): what each row
 * of cells sums, one 64-bit fixed-point partial each. u, v, w are a cell's centred velocity, S its strain
 * rate, nu_t its eddy viscosity, e its subgrid energy and a its drag density. */
#define FW_TERM_CELLS 0 /* fluid cells (1 each, unscaled) */
#define FW_TERM_U 1
#define FW_TERM_V 2
#define FW_TERM_W 3
#define FW_TERM_UU 4
#define FW_TERM_VV 5
#define FW_TERM_WW 6
#define FW_TERM_UUU 7
#define FW_TERM_WWW 8
#define FW_TERM_UW 9
#define FW_TERM_VW 10
#define FW_TERM_U_DIFF 11 /* -2 nu_t S_xz */
#define FW_TERM_V_DIFF 12 /* -2 nu_t S_yz */
#define FW_TERM_E 13
#define FW_TERM_LAD 14
#define FW_TERM_SPEED 15 /* |(u, v, w)|: its largest value only, no sum */
#define FW_PLANE_TERMS 16
/* A cell's scaled term stays within 2^FW_PLANE_CELL_BITS, so that FW_PLANE_FLUSH_CHUNKS of them add in a
 * 32-bit lane before it is widened to 64 bits. */
#define FW_PLANE_CELL_BITS 27
#define FW_PLANE_FLUSH_CHUNKS ((1 << (31 - FW_PLANE_CELL_BITS)) - 1)

/* The wind grid: a MAC grid of nx*ny*nz cubic cells of size h.
 * Storage is x-fastest. u lives on x-faces ((nx+1)*ny*nz values), v on y-faces (nx*(ny+1)*nz),
 * w on z-faces (nx*ny*(nz+1)); pressure and masks at cell centres (nx*ny*nz). */
typedef struct FwGrid {
  fw_int nx, ny, nz; /* cells */
  fw_int bc[6];      /* FW_BC_* per face, indexed by FW_FACE_* */
  float h;           /* cell size, m */
  float origin[3];   /* world position of the domain's minimum corner, m */
  fw_int ox, oy;     /* a rank's block: the domain's cell index of local cell (0, 0) along x, y; 0 alone */
  fw_int wrap[2];    /* a rank's block on a cut periodic axis x, y: the domain's cells along it, else 0 */
  fw_int domain[2];  /* the domain's cells along x, y (nx, ny alone): where a point sample clamps */
} FwGrid;

/* One level of the pressure hierarchy (the fine grid is level 0), or a rank's block of it with its halo.
 * periodic: bit a set when axis a (0 x, 1 y, 2 z) wraps around inside these cells. ox, oy: the level's global
 * cell index of local cell (0, 0), 0 for a whole level; the red-black colour (i + j + k) % 2 and the pairing
 * of fine and coarse cells are taken in global indices (docs/parallel.md). */
typedef struct FwLevel {
  fw_int nx, ny, nz;
  fw_int periodic;
  fw_int ox, oy;
} FwLevel;

/* What changes from step to step, passed by value to the kernels that need it.
 * Synthetic inflow turbulence (fluid/TurbulenceBox, docs/design.md "Turbulence"): a periodic box of
 * unit-sigma velocity fluctuations, stored after the nz profile factors in the kernels' `inflow` buffer, is
 * swept through the inflow faces (Taylor's frozen turbulence): a face at world position x adds
 * turbulence_sigma * taper * box(x - turbulence_offset), taper = min(1, profile / FW_TURBULENCE_FULL_SHAPE).
 * turbulence_sigma 0: no turbulence. */
/* The inflow turbulence has its full sigma where the mean profile reaches this fraction of the reference
 * speed, and tapers linearly to 0 where the mean wind does. In the surface layer sigma_u stays near 2.5 u*
 * at every height (so the intensity rises toward the ground), which a taper by the profile itself would cut;
 * a taper is still needed where the mean wind is 0 (below z0 + d of a log law). */
#define FW_TURBULENCE_FULL_SHAPE 0.5f
typedef struct FwStep {
  float dt;                   /* s */
  float time;                 /* simulated time at the start of the step, s */
  float ambient[3];           /* ambient wind at the reference height, m/s (vector, x east, y north, z up) */
  float turbulence_sigma;     /* sigma_u of the inflow turbulence now, m/s (0: off) */
  float turbulence_offset[3]; /* how far the frozen box has travelled, m, kept within one box length */
  fw_int turbulence_cells[3]; /* box points along x, y, z */
  float turbulence_spacing;   /* box point spacing, m */
} FwStep;

/* The canopy's drag law (fluid/DragLaw.hpp) as the drag kernels read it: C_D(|u|) / C_D0 =
 * (max(|u|, lowest_speed) * inverse_reference_speed)^exponent, 1 where exponent is 0. */
typedef struct FwDragLaw {
  float exponent;
  float lowest_speed;            /* m/s */
  float inverse_reference_speed; /* s/m */
  float unused;                  /* keeps the struct four floats wide */
} FwDragLaw;

/* Ghost layers on every side of a padded velocity copy (kernels/fluid_ghosts.cl, host/stages/FluidStages):
 * the widest stencil, fifth-order upwind advection (kernels/fluid_upwind.cl), reaches three faces past the
 * face it updates across a periodic boundary. */
#define FW_PAD 3

/* The order of one upwind flux (fluid/UpwindStencil.hpp): two bits a flux, for the lower and the upper flux
 * of a face along each axis a at bit FW_UPWIND_SHIFT(a, side), side 0 lower, 1 upper. */
#define FW_UPWIND_FIRST 0
#define FW_UPWIND_THIRD 1
#define FW_UPWIND_FIFTH 2
#define FW_UPWIND_BITS 3
#define FW_UPWIND_SHIFT(a, side) (4 * (a) + 2 * (side))

/* The prescribed inflow shell: with the inflow turbulence on, every prescribed face value of a step (the
 * inflow faces of the normal component and the ghosts beyond an inflow face) is sampled once per step
 * (kernels/fluid_boundaries.cl fill_inflow_shell) into this shell, which follows the turbulence box in the
 * kernels' `inflow` buffer, so that the kernels reading those values (kernels/common.cl inflow_face_value)
 * do not each sample the box (a random access per value into a box far larger than the caches).
 * Layout: for each domain face f (FW_FACE_* order, normal to axis a = f / 2) and each component c, a block
 * of FW_SHELL_LAYERS layers along a (own face index -FW_PAD .. 0 on a low face, extent - 1 .. extent - 1 +
 * FW_PAD on a high one), each layer the face indices -FW_PAD .. n + FW_PAD of the other two axes (n their
 * cells; the lower-numbered axis fastest). Blocks of every face are laid out, filled only on inflow faces. */
#define FW_SHELL_LAYERS (FW_PAD + 1)

/* Face indices the shell holds along an axis of `cells` cells. */
static inline fw_int fw_shell_span(fw_int cells) {
  return cells + 1 + 2 * FW_PAD;
}

/* Floats of one component's block on a face normal to axis a, on a grid of nx * ny * nz cells. */
static inline fw_int fw_shell_block(fw_int nx, fw_int ny, fw_int nz, fw_int a) {
  const fw_int b1 = a == 0 ? ny : nx, b2 = a == 2 ? ny : nz;
  return FW_SHELL_LAYERS * fw_shell_span(b1) * fw_shell_span(b2);
}

/* Where the blocks of face f start in the shell (f = 6: the shell's length). */
static inline fw_int fw_shell_face_offset(fw_int nx, fw_int ny, fw_int nz, fw_int f) {
  fw_int offset = 0;
  for (fw_int before = 0; before < f; ++before) offset += 3 * fw_shell_block(nx, ny, nz, before / 2);
  return offset;
}

/* A gust: a Gaussian ball of extra velocity with a 1-cos envelope in time, travelling at a constant
 * velocity. A parcel moving with the ball sees its velocity rise by peak_speed * 0.5 * (1 - cos(2 pi tau/T))
 * * exp(-(r/radius)^2) along `direction` and fall back to zero at tau = T. */
typedef struct FwGust {
  float start;        /* s */
  float duration;     /* T, s */
  float peak_speed;   /* m/s */
  float radius;       /* Gaussian e-folding radius, m */
  float center[3];    /* world position at `start`, m */
  float travel[3];    /* velocity of the ball's centre, m/s */
  float direction[3]; /* unit vector of the added velocity */
} FwGust;

/* Deardorff's subgrid energy model (fluid/SubgridTke.hpp, kernels/subgrid_tke.cl): its per-cell factors
 * at the grid's cell size, [0] for an open cell, [1] for a cell on a wall (fluid::wall_cells), and its
 * constants, filled from fluid::tke_coefficients and the constants there. */
typedef struct FwTke {
  float viscosity_length[2]; /* C_m l, m: nu_t = C_m l sqrt(e) */
  float dissipation_rate[2]; /* C_eps / l, 1/m: dissipation C_eps e^(3/2) / l */
  float canopy_sink;         /* s of the canopy's sink -s k |U| e */
  float wake_fraction;       /* share of the drag's work k |U|^3 produced as e */
  float floor;               /* the smallest e of a fluid cell, m^2/s^2 */
  float inflow;              /* e beyond an inflow face, m^2/s^2 */
} FwTke;

/* --- Trees (docs/design.md, "Numerics: Trees: Instances"; Diener 2008, figure 5) ---------------------------
 * Per-species arrays are packed back to back (trees/Forest.hpp, ForestPacking); the offsets below index them.
 * Flat per-instance arrays (modal state and forces, displacements, sampled wind) hold each instance's block
 * at the instance's own offsets. */

/* Most wind samples (height bands) a species may have: the wind load kernel keeps one instance's sampled
 * loads in private memory. */
#define FW_MAX_TREE_SAMPLES 16

/* One species: sizes and where its constants start in the packed arrays. */
typedef struct FwSpecies {
  fw_int node_count;          /* n, skeleton nodes */
  fw_int mode_count;          /* m */
  fw_int sample_count;        /* S, wind samples, 1..FW_MAX_TREE_SAMPLES */
  fw_int shape_offset;        /* node shapes, floats: [mode 3n + 3 node + axis]; strong-wind dv, dw: 3 n m
                                 floats each, in walk blocks (trees/Forest.hpp) */
  fw_int projection_offset;   /* projections, floats: mode-major, [mode 3S + 3 sample + axis], kg^1/2/m */
  fw_int sample_point_offset; /* sample points, floats: [3 sample + axis], m, skeleton frame */
  fw_int modal_offset;        /* omega (rad/s), damping ratio zeta, strong-wind b: one float each per mode */
  fw_int skeleton_offset;     /* first of its n entries in the skeleton walk (2 ints each: node, parent) and
                                 rest elements (3 floats each, in walk blocks), both in walk order
                                 (trees/Forest.hpp) */
} FwSpecies;

/* One tree instance: world position x + scale R(yaw) p of a skeleton point p; R turns counter-clockwise
 * about +z seen from above. */
typedef struct FwTreeInstance {
  fw_int species;       /* index into the species table */
  fw_int mode_offset;   /* first of its m entries in the flat modal state and forces */
  fw_int node_offset;   /* first of its n nodes in the flat displacements */
  fw_int sample_offset; /* first of its S samples in the flat sampled wind */
  float position[3];    /* world position of the skeleton origin (the root), m */
  float cos_yaw;        /* cos and sin of the yaw angle */
  float sin_yaw;
  float scale; /* s > 0: lengths times s, frequencies over s */
} FwTreeInstance;

/* --- Element tree models (trees/TreeDynamics.hpp: rigid_bodies, springs) ---------------------------------
 * A species moved by an element model has a table of FwBranch entries (trees/BranchElements.hpp), n per
 * species from FwSpecies.skeleton_offset, in the skeleton's topological order: entry 0 the root, without an
 * element. Values at scale 1; kernels/tree_branches.cl scales them per instance. */
#define FW_DYNAMICS_MODAL 0
#define FW_DYNAMICS_RIGID_BODIES 1
#define FW_DYNAMICS_SPRINGS 2

typedef struct FwBranch {
  fw_int node;         /* the element's outer node, index within the tree */
  fw_int parent_node;  /* its base node, where its joint is */
  fw_int parent_entry; /* the table entry of parent_node, 0 at the root */
  float rest[3];       /* node minus parent node at rest, m, skeleton frame */
  float centre[3];     /* the element's midpoint at rest, m, skeleton frame */
  float length;        /* m */
  float mass;          /* kg */
  float axial_inertia; /* kg m^2 */
  float stiffness[6];  /* K_e, N m/rad: xx yy zz xy xz yz */
  float branch_drag;   /* 1/2 rho_air C_Db D_e, kg/m^2 */
  float leaf_drag;     /* 1/2 rho_air C_Df lambda_e, kg/m^2 */
  float spring;        /* k = E D^4 / (4 L^3), N/m */
} FwBranch;

/* A species' element model (trees/TreeDynamics.hpp), at scale 1. */
typedef struct FwBranchSpecies {
  fw_int model;         /* FW_DYNAMICS_* */
  fw_int normal_drag;   /* 1: the wood drags with the wind normal to it only (branch_normal_drag) */
  float damping;        /* rigid_bodies: beta = 2 zeta / omega_1 of C = beta K, s */
  float max_angle;      /* springs: the largest bend, rad */
  float sway_amplitude; /* springs: the stochastic sine's amplitude at the largest bend */
  float sway_omega;     /* springs: its angular frequency 2 pi f, rad/s */
} FwBranchSpecies;

/* A tree moved by an element model: its instance, its first entry in the flat element arrays (joint state,
 * sampled wind, orientation) and the id that seeds its phases (Forest::id). */
typedef struct FwBranchTree {
  fw_int instance;
  fw_int entry_offset;
  fw_int id;
} FwBranchTree;

/* The joint state of an entry in the flat arrays: its angle and rate (rotation vectors, rad and rad/s). */
#define FW_JOINT_FLOATS 6
/* The rigid bodies' theta-method weight w (trees/RigidBranches.hpp): 1/2 is the trapezoidal rule, 1 backward
 * Euler. */
#define FW_RIGID_IMPLICIT_WEIGHT 0.6f
/* Floats a rigid tree's recursion keeps per entry between its passes (kernels/tree_branches.cl). */
#define FW_RIGID_SCRATCH_FLOATS 33
/* Floats the pose keeps per entry while it walks a tree (kernels/tree_branches.cl branch_deform): its
 * orientation, a quaternion. */
#define FW_POSE_FLOATS 4

/* b_e of entry `entry` of tree `id` (trees/SpringBranches.hpp spring_phases), as the fraction of a turn
 * fw_phase_bits / 2^24: an integer hash (Wellons' lowbias32), the same bits on the host and the device. */
#define FW_PHASE_BITS 24
static inline fw_uint fw_phase_bits(fw_uint id, fw_uint entry) {
  fw_uint x = id * 0x9E3779B9u ^ entry;
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x >> (32 - FW_PHASE_BITS);
}

/* Leaves (docs/leaves.md). State of a leaf, one byte each (trees/LeafState.hpp). */
#define FW_LEAF_ATTACHED 0
#define FW_LEAF_FLYING 1
#define FW_LEAF_LANDED 2
#define FW_LEAF_EXITED 3
/* A slot whose leaf moved on to the rank whose block it flew into (host/stages/LeafStages): never stepped,
 * never written. */
#define FW_LEAF_MOVED 4
/* Flutter models (trees/LeafSettings.hpp FlutterModel). */
#define FW_FLUTTER_NONE 0
#define FW_FLUTTER_PSEUDO_BRANCH 1
#define FW_FLUTTER_STOCHASTIC 2
/* Leaf counters, one fw_int each in the counters buffer. */
#define FW_LEAF_COUNT_SHED 0
#define FW_LEAF_COUNT_LANDED 1
#define FW_LEAF_COUNT_EXITED 2
/* Over ranks, each step: the leaves found outside the block's own columns (their slots listed for the host),
 * and the sub-steps that reached past the block's halo (the run stops: the halo is too narrow). */
#define FW_LEAF_COUNT_LEAVING 3
#define FW_LEAF_COUNT_PAST_HALO 4
#define FW_LEAF_COUNTERS 5
/* A leaf moving to another rank (kernels/leaves.cl leaves_pack): its position, velocity, normal and flight
 * (4 floats each), with its state in the position's 4th float and its flight drag in the velocity's. */
#define FW_LEAF_PACKED_FLOATS 16

/* A species' leaf parameters at scale 1 (an instance of scale s: side, lever times s, area, mass times s^2).
 */
typedef struct FwLeafSpecies {
  fw_int model;          /* FW_FLUTTER_* */
  fw_int leaf_offset;    /* first of its leaves in the rest-leaf table */
  fw_int leaf_count;     /* leaves of one instance */
  float side;            /* l, m */
  float lever;           /* r, anchor to blade centre, m */
  float area;            /* a, m^2 */
  float mass;            /* m, kg */
  float omega;           /* flutter angular frequency, rad/s */
  float damping_ratio;   /* zeta */
  float amplitude[3];    /* W_H, W_V, W_R, rad */
  float roll_coupling;   /* a */
  float reference_speed; /* U_ref, m/s */
  float flight_drag;     /* k = rho C_D / (2 sigma), 1/m */
} FwLeafSpecies;

/* The rest leaves of every species on the device, one table of floats, field-major: field f of rest leaf r
 * at f * stride + r, so that consecutive leaves' fields load as vectors (kernels/lanes.cl). The stride is
 * the rest-leaf count plus FW_LANES, so that the last leaves' lanes may load past the end. Skeleton frame
 * (trees/SpeciesLeaves.hpp RestLeaf); a vector field takes 3 rows (x, y, z). */
#define FW_REST_ANCHOR 0        /* m */
#define FW_REST_PETIOLE 3       /* unit: from the anchor to the blade centre */
#define FW_REST_HINGE 6         /* unit: the pseudo-branch's axis, normal to the petiole */
#define FW_REST_NORMAL 9        /* unit: the blade's normal */
#define FW_REST_SWING 12        /* hinge x normal: the way the normal turns as theta grows */
#define FW_REST_TUMBLE_AXIS 15  /* unit: the horizontal axis a flying blade tumbles about */
#define FW_REST_PHASE 18        /* 3 rows: the stochastic angles' phases, rad */
#define FW_REST_FREQUENCY 21    /* 3 rows: their frequencies, Hz */
#define FW_REST_HINGE_NORMAL 24 /* hinge . normal */
#define FW_REST_KAPPA 25 /* (hinge x petiole) . normal: the blade's lever factor, the same at every theta */
#define FW_REST_ALONG 26 /* t along the element, parent node to child node */
#define FW_REST_STRENGTH 27 /* petiole strength, N */
#define FW_REST_FIELDS 28

/* --- Storm damage (trees/TreeDamage.hpp, docs/damage.md) -------------------------------------------------
 * What happened to a tree: FwTreeDamage.state. */
#define FW_TREE_STANDING 0
#define FW_TREE_BROKEN 1
#define FW_TREE_OVERTURNED 2

/* A species' stem loads (trees/StemLoads.hpp) and critical moments, at scale 1, as lanes of FW_LANES: its
 * J sections and then its root make J + 1 lanes, in blocks of FW_LANES (the last block padded with zero
 * maps and a critical moment of 1). maps: per block 4 rows (the elastic moment on e1, on e2, the weight's
 * on e1, on e2; for the root's lane its x and y), each m modes of FW_LANES floats (N m per unit q).
 * sections: per block 2 rows of FW_LANES: the height above the root (m) and the critical moment (N m: M_b
 * of the section, M_o in the root's lane). The maps of a species an element model moves are not read: its
 * trees' moments come from their joints (FwStemAxis). */
typedef struct FwStem {
  fw_int section_count;  /* J */
  fw_int block_count;    /* ceil((J + 1) / FW_LANES) */
  fw_int map_offset;     /* first float of its maps: 4 m FW_LANES floats a block */
  fw_int section_offset; /* first float of its sections: 2 FW_LANES floats a block */
  fw_int axis_offset;    /* first of its J FwStemAxis (the element trees' stem) */
} FwStem;

/* A stem section as the element trees' loads see it (trees/BranchStemLoads.hpp BranchStem): the stem's unit
 * axis at rest (to the next stem node), skeleton frame, and its node's entry in the species' FwBranch table.
 * Per entry of that table (in its layout, from FwSpecies.skeleton_offset) the loads read 2 ints: the section
 * at its joint (its element starts at that stem node) or -1, and the highest section its element lies above
 * (-1 for the root's entry). */
typedef struct FwStemAxis {
  float axis[3];
  fw_int entry;
} FwStemAxis;

/* kernels/tree_loads.cl branch_tree_loads' scratch, per work-item: per section the joint moments at it (3)
 * and the weight of the elements it lies under, sum m u_c and sum m (4); per entry its orientation (a
 * quaternion, 4) and its node's displacement (3). */
#define FW_LOADS_SECTION_FLOATS 7
#define FW_LOADS_ENTRY_FLOATS 7

/* A tree's damage record: what the device updates every step (trees/TreeDamage.hpp TreeDamageRecord). */
typedef struct FwTreeDamage {
  fw_int state;          /* FW_TREE_* */
  fw_int failed_section; /* the section that broke, -1 */
  float time;            /* s: when it failed */
  float break_height;    /* m above the root (0 when overturned) */
  float top_wind[3];     /* m/s at its top (its highest wind sample) when it failed */
  float max_utilisation; /* the largest applied-to-critical ratio over the run */
  float max_base_moment; /* N m, the largest root moment over the run */
  float utilisation;     /* the last step's largest */
} FwTreeDamage;

/* A failed tree falling on an output frame (host/stages/DamageStages enqueue_falls; docs/damage.md, "What
 * follows a failure"): the part above its pivot node (the broken section's node, or the root for an
 * overturned tree) turned by the angle about the horizontal axis z x direction, and dropped. */
typedef struct FwFall {
  fw_int instance; /* the tree */
  fw_int pivot;    /* its pivot node, within the tree */
  float cos_angle; /* cos and sin of the angle it has turned through, from upright */
  float sin_angle;
  float direction[2]; /* the horizontal unit vector it falls toward, world frame */
  float drop;         /* m: how far the falling part has come down (a broken top, to the ground) */
} FwFall;

#endif
