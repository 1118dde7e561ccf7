// The prose docs/scenario.md prints for each key of kSolverKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/SolverKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "solver.pressure",
     .description = "Pressure solver. `cg`: conjugate gradients preconditioned by a multigrid V-cycle. "
                    "`multigrid`: V-cycles alone. `jacobi`: a fixed number of Jacobi sweeps (the baseline)."},
    {.path = "solver.tolerance",
     .bounds_why = why::kTolerance,
     .description = "Relative residual `\\|\\|b - A p\\|\\| / \\|\\|b\\|\\|` at which `cg` and `multigrid` "
                    "stop. In float32, values below about 1e-5 cannot be reached."},
    {.path = "solver.max_iterations",
     .bounds_why = why::kIterations,
     .description = "Most CG iterations or V-cycles per solve (`cg`, `multigrid`)."},
    {.path = "solver.jacobi_iterations",
     .bounds_why = why::kIterations,
     .description = "Sweeps per solve (`jacobi`)."},
    {.path = "solver.advection",
     .description = "Advection scheme of the momentum. `semi_lagrangian`: back-traced, stable at any "
                    "Courant number, damps eddies under about 15 cells. `maccormack` (clamped) keeps "
                    "gusts sharper. `upwind5`: flux-form fifth-order upwind with three Runge-Kutta stages "
                    "(Wicker & Skamarock 2002, as PALM and WRF), conservative, resolves eddies down to "
                    "about 6 to 7 cells, stable up to a summed Courant number of 1.2; third and then "
                    "first order over the last cells before walls, inflow and outflow faces and solids."},
    {.path = "solver.stage_projection",
     .description = "With `upwind5`: `final_stage` projects once a step, after the last Runge-Kutta stage; "
                    "`every_stage` also projects the first two stages (three pressure solves a step)."},
    {.path = "solver.vorticity_confinement",
     .default_note = "`0` (off)",
     .bounds_why = why::kConfinement,
     .description = "Vorticity confinement strength epsilon."},
    {.path = "solver.subgrid",
     .description =
         "Model of the subgrid stress. `smagorinsky`: the eddy viscosity `(C_s h)^2 \\|S\\|` of "
         "`smagorinsky_constant`, on while that is above 0. `tke`: Deardorff's 1.5-order closure "
         "(as PALM): each cell carries a subgrid kinetic energy e, advected, diffused, produced by "
         "the strain and by the canopy's wakes, dissipated and drained by the canopy's drag; the "
         "eddy viscosity is `C_m l sqrt(e)`, C_m = 0.1, l = h (0.9 h on a wall). With `tke`, leave "
         "`smagorinsky_constant` out. docs/numerics.md, \"Subgrid energy\"."},
    {.path = "solver.smagorinsky_constant",
     .default_note = "`0` (off); `0.16` with `advection: upwind5`",
     .bounds_why = why::kSmagorinsky,
     .description =
         "With `subgrid: smagorinsky`: the constant C_s of the subgrid eddy viscosity `nu_t = (C_s h)^2 "
         "\\|S\\|`, h = `domain.cell_size` and `\\|S\\| = sqrt(2 S_ij S_ij)` the resolved strain rate: "
         "the stress of the eddies smaller than a cell, which drains energy at the grid scale. Typical "
         "0.1 to 0.2 (0.17 for isotropic turbulence, Lilly 1967; smaller in shear near walls). "
         "`upwind5` dissipates too little on its own, so it gets 0.16 unless this names another (`0` "
         "turns it off): the smallest constant that keeps decaying turbulence on the -5/3 line, without "
         "a pile-up, down to 6 cells (docs/numerics.md). `semi_lagrangian` and `maccormack` drain the "
         "cascade themselves."},
};

}  // namespace

std::span<const KeyDocs> solver_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
