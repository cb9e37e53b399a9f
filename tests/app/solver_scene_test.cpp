// Solver keys in scene files: "simulation.integrator", "simulation.linear_solver",
// "simulation.constraints" and "simulation.collision_friction" land in sim::SimSettings; every
// mistake names its key path. And a parsed scene drives the simulator with them.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "sim/pins.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

using test::parse_json_scene;
using test::scene_error_of;

// A valid scene with every solver key set, to be changed one key at a time.
Json solver_scene() {
  return Json::parse(R"({
    "description": "test scene with solver keys",
    "cloth": {"size": ["40 cm", "40 cm"], "resolution": [9, 9],
              "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
    "obstacles": [{"plane": {"point": [0, 0, 0], "normal": [0, 0, 1]}}],
    "simulation": {
      "integrator": "implicit_euler",
      "linear_solver": "eigen_ldlt",
      "implicit_solver": "conjugate_gradient",
      "cg_tolerance": 1e-3,
      "cg_preconditioner": "block_jacobi",
      "constraints": {"method": "fast_projection", "edges": "triangle_edges",
                      "tolerance": 1e-4, "max_iterations": 50},
      "collision_friction": 0.45
    }
  })");
}

TEST(SolverScene, EveryKeyLandsInSimSettings) {
  const sim::SimSettings s = parse_json_scene(solver_scene()).sim;
  EXPECT_EQ(s.integrator, sim::Integrator::implicit_euler);
  EXPECT_EQ(s.sparse_backend, sim::SparseBackend::eigen_ldlt);
  EXPECT_EQ(s.implicit_solve, sim::ImplicitSolve::conjugate_gradient);
  EXPECT_EQ(s.implicit_cg_tolerance, 1e-3);
  EXPECT_EQ(s.implicit_cg_preconditioner, sim::CgPreconditioner::block_jacobi);
  EXPECT_EQ(s.projection.method, sim::ProjectionMethod::fast_projection);
  EXPECT_EQ(s.projection.edges, sim::ConstrainedEdges::triangle_edges);
  EXPECT_EQ(s.projection.tolerance, 1e-4);
  EXPECT_EQ(s.projection.max_iterations, 50);
  EXPECT_EQ(s.collision_friction, 0.45);
}

TEST(SolverScene, OmittedKeysTakeTheStructDefaults) {
  Json j = solver_scene();
  j.erase("simulation");
  const sim::SimSettings s = parse_json_scene(j).sim;
  const sim::SimSettings defaults;
  const sim::ProjectionSettings projection;
  EXPECT_EQ(s.integrator, sim::Integrator::symplectic_euler);
  EXPECT_EQ(s.sparse_backend, sim::default_sparse_backend());
  EXPECT_EQ(s.implicit_solve, defaults.implicit_solve);
  EXPECT_EQ(s.implicit_cg_tolerance, defaults.implicit_cg_tolerance);
  EXPECT_EQ(s.implicit_cg_preconditioner, sim::CgPreconditioner::automatic);
  EXPECT_EQ(s.projection.method, sim::ProjectionMethod::none);
  EXPECT_EQ(s.projection.edges, projection.edges);
  EXPECT_EQ(s.projection.tolerance, 1e-3);
  EXPECT_EQ(s.projection.max_iterations, 100);
  EXPECT_EQ(s.projection.max_stretch, projection.max_stretch);
  EXPECT_EQ(s.collision_friction, 0.0);
  EXPECT_EQ(s.collision_friction, defaults.collision_friction);
  // A fast projection with only its method given keeps the other defaults.
  j["simulation"] = {{"constraints", {{"method", "fast_projection"}}}};
  const sim::ProjectionSettings p = parse_json_scene(j).sim.projection;
  EXPECT_EQ(p.method, sim::ProjectionMethod::fast_projection);
  EXPECT_EQ(p.edges, sim::ConstrainedEdges::warp_weft);
  EXPECT_EQ(p.tolerance, projection.tolerance);
  EXPECT_EQ(p.max_iterations, projection.max_iterations);
  EXPECT_EQ(p.reuse_iterations, projection.reuse_iterations);
  j["simulation"]["constraints"]["reuse_iterations"] = 0;
  EXPECT_EQ(parse_json_scene(j).sim.projection.reuse_iterations, 0);
}

TEST(SolverScene, EachChoiceParses) {
  Json j = solver_scene();
  j["simulation"]["integrator"] = "symplectic_euler";
  EXPECT_EQ(parse_json_scene(j).sim.integrator, sim::Integrator::symplectic_euler);
  j["simulation"]["constraints"]["edges"] = "warp_weft";
  EXPECT_EQ(parse_json_scene(j).sim.projection.edges, sim::ConstrainedEdges::warp_weft);
  j["simulation"]["constraints"] = {
      {"method", "pairwise"}, {"max_iterations", 8}, {"max_stretch", 0.1}, {"tolerance", 0.1}};
  const sim::ProjectionSettings p = parse_json_scene(j).sim.projection;
  EXPECT_EQ(p.method, sim::ProjectionMethod::pairwise);
  EXPECT_EQ(p.max_iterations, 8);
  EXPECT_EQ(p.max_stretch, 0.1);
  EXPECT_EQ(p.tolerance, 0.1);
  j["simulation"]["constraints"] = {{"method", "none"}};
  EXPECT_EQ(parse_json_scene(j).sim.projection.method, sim::ProjectionMethod::none);
  j["simulation"]["collision_friction"] = 0;
  EXPECT_EQ(parse_json_scene(j).sim.collision_friction, 0.0);
  for (const sim::SparseBackend backend : sim::available_sparse_backends()) {
    j["simulation"]["linear_solver"] = sim::sparse_backend_name(backend);
    EXPECT_EQ(parse_json_scene(j).sim.sparse_backend, backend);
  }
}

TEST(SolverScene, WrongEnumsListTheChoices) {
  Json j = solver_scene();
  j["simulation"]["integrator"] = "rk9";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.integrator: expected one of 'symplectic_euler', "
            "'implicit_euler', 'explicit_euler', 'rk4', 'velocity_verlet', 'central_difference', "
            "'dynamic_relaxation', got the string 'rk9'");
  j = solver_scene();
  j["simulation"]["linear_solver"] = "umfpack";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.linear_solver: expected one of 'cholmod', 'eigen_ldlt', got "
            "the string 'umfpack'");
  j = solver_scene();
  j["simulation"]["constraints"]["method"] = "goldenthal";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.method: expected one of 'none', "
            "'fast_projection', 'pairwise', got the string 'goldenthal'");
  j = solver_scene();
  j["simulation"]["constraints"]["edges"] = "all";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.edges: expected one of 'warp_weft', "
            "'triangle_edges', got the string 'all'");
}

// "adaptive" time steps (sim/adaptive_step.h): the keyword, its settings, and their mistakes.
TEST(SolverScene, AnAdaptiveTimeStepParsesWithItsSettings) {
  Json j = solver_scene();
  j["simulation"]["time_step"] = "adaptive";
  sim::SimSettings s = parse_json_scene(j).sim;
  EXPECT_TRUE(s.time_step.is_adaptive());
  EXPECT_EQ(s.time_step.adaptive.max_step_s, sim::AdaptiveStepSettings{}.max_step_s);
  j["simulation"]["adaptive_step"] = {
      {"min_step", "0.5 ms"}, {"max_step", "20 ms"}, {"max_prediction_strain", 0.02}};
  s = parse_json_scene(j).sim;
  EXPECT_DOUBLE_EQ(s.time_step.adaptive.min_step_s, 5e-4);
  EXPECT_DOUBLE_EQ(s.time_step.adaptive.max_step_s, 0.02);
  EXPECT_EQ(s.time_step.adaptive.max_prediction_strain, 0.02);
  EXPECT_EQ(parse_json_scene(solver_scene()).sim.time_step.kind, sim::TimeStep::Kind::automatic);
}

TEST(SolverScene, RestingContactsNeedTheImplicitSolve) {
  Json j = solver_scene();
  j["simulation"]["integrator"] = "implicit_euler";
  j["simulation"]["resting_contacts"] = true;
  EXPECT_TRUE(parse_json_scene(j).sim.resting_contacts);
  j["simulation"]["integrator"] = "symplectic_euler";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.resting_contacts: applies only with integrator "
            "\"implicit_euler\" (it holds contacts inside the implicit solve)");
}

TEST(SolverScene, BendingInStepIsReadAndImplicitNeedsTheImplicitSolve) {
  Json j = solver_scene();
  EXPECT_EQ(parse_json_scene(j).sim.bending_in_step, sim::BendingInStep::automatic);
  j["simulation"]["integrator"] = "implicit_euler";
  j["simulation"]["bending_in_step"] = "implicit";
  EXPECT_EQ(parse_json_scene(j).sim.bending_in_step, sim::BendingInStep::implicit);
  j["simulation"]["bending_in_step"] = "explicit";
  EXPECT_EQ(parse_json_scene(j).sim.bending_in_step, sim::BendingInStep::explicit_forces);
  j["simulation"]["bending_in_step"] = "sometimes";
  EXPECT_CONTAINS(scene_error_of(j), "simulation.bending_in_step: expected one of 'auto', "
                                     "'explicit', 'implicit', got the string 'sometimes'");
  j["simulation"]["bending_in_step"] = "implicit";
  j["simulation"]["integrator"] = "symplectic_euler";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.bending_in_step: \"implicit\" applies only with integrator "
            "\"implicit_euler\" (the explicit integrators have no matrix to take it into)");
}

TEST(SolverScene, AdaptiveStepMistakesNameTheirKeys) {
  Json j = solver_scene();
  j["simulation"]["time_step"] = "adaptve";
  EXPECT_CONTAINS(scene_error_of(j), "simulation.time_step: expected 'auto', 'adaptive' or a time");
  j["simulation"]["time_step"] = "1 ms";
  j["simulation"]["adaptive_step"] = {{"max_step", "20 ms"}};
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.adaptive_step: applies only with time_step \"adaptive\"");
  j["simulation"]["time_step"] = "adaptive";
  j["simulation"]["adaptive_step"] = {{"min_step", "30 ms"}, {"max_step", "20 ms"}};
  EXPECT_CONTAINS(scene_error_of(j), "simulation.adaptive_step.max_step: expected at least min_step");
  j["simulation"]["adaptive_step"] = {{"max_prediction_strain", 0}};
  EXPECT_CONTAINS(scene_error_of(j), "simulation.adaptive_step.max_prediction_strain");
  // It follows fast projection's iterations: another method or integrator is refused.
  j["simulation"].erase("adaptive_step");
  j["simulation"]["constraints"] = {{"method", "none"}};
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: simulation.time_step: \"adaptive\" follows "
                                     "fast projection's iterations");
  j["simulation"]["constraints"] = {{"method", "fast_projection"}};
  j["simulation"]["integrator"] = "symplectic_euler";
  EXPECT_CONTAINS(scene_error_of(j), "simulation.time_step: \"adaptive\" follows");
  // A frame takes at most a million steps, of a fixed step or of the adaptive step's max_step.
  j["simulation"]["integrator"] = "implicit_euler";
  j["simulation"]["adaptive_step"] = {{"min_step", "1e-9 s"}, {"max_step", "1e-9 s"}};
  EXPECT_CONTAINS(scene_error_of(j), "simulation.adaptive_step.max_step: a time of");
  // …and of its min_step, were the step to shrink to it (1e-300 s used to run for a minute).
  j["simulation"]["adaptive_step"] = {{"min_step", "1e-300 s"}};
  EXPECT_CONTAINS(scene_error_of(j), "simulation.adaptive_step.min_step: a time of");
  j["simulation"].erase("adaptive_step");
  j["simulation"]["time_step"] = "1e-9 s";
  EXPECT_CONTAINS(scene_error_of(j), "simulation.time_step: a time of");
}

TEST(SolverScene, CholmodIsAnErrorOnlyWhenTheBuildLacksIt) {
  Json j = solver_scene();
  j["simulation"]["linear_solver"] = "cholmod";
  const auto available = sim::available_sparse_backends();
  if (std::find(available.begin(), available.end(), sim::SparseBackend::cholmod) !=
      available.end()) {
    EXPECT_EQ(parse_json_scene(j).sim.sparse_backend, sim::SparseBackend::cholmod);
  } else {
    EXPECT_EQ(scene_error_of(j),
              "scene.json: simulation.linear_solver: expected a back-end this build has "
              "('eigen_ldlt'), got 'cholmod', which it was built without");
  }
}

TEST(SolverScene, OutOfRange) {
  Json j = solver_scene();
  j["simulation"]["constraints"]["tolerance"] = -1e-3;
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.tolerance: expected a number > 0, got -0.001");
  j["simulation"]["constraints"]["tolerance"] = 0;
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.tolerance: expected a number > 0, got 0");
  j = solver_scene();
  j["simulation"]["constraints"]["max_iterations"] = 0;
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.max_iterations: expected an integer in [1, "
            "2147483647], got 0");
  j["simulation"]["constraints"]["max_iterations"] = 2.5;
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: simulation.constraints.max_iterations: expected an integer");
  j = solver_scene();
  j["simulation"]["constraints"] = {{"method", "pairwise"}, {"max_stretch", -0.1}};
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.max_stretch: expected a number ≥ 0, got -0.1");
  j = solver_scene();
  j["simulation"]["constraints"] = {{"method", "pairwise"}, {"reuse_iterations", 8}};
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.reuse_iterations: expected only with method "
            "'fast_projection' (it has no effect otherwise), got method 'pairwise'");
  j["simulation"]["constraints"] = {{"method", "fast_projection"}, {"reuse_iterations", -1}};
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.reuse_iterations: expected an integer in [0, "
            "1000], got -1");
  j = solver_scene();
  j["simulation"]["cg_tolerance"] = 1.0;
  EXPECT_EQ(scene_error_of(j), "scene.json: simulation.cg_tolerance: expected a number in (0, 1), got 1.0");
  j["simulation"]["cg_tolerance"] = 1e-3;
  j["simulation"]["cg_preconditioner"] = "amg";
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.cg_preconditioner: expected one of 'auto', 'multigrid', "
            "'lines', 'block_jacobi', got the string 'amg'");
  j["simulation"]["implicit_solver"] = "cg";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: simulation.implicit_solver:");
  EXPECT_CONTAINS(scene_error_of(j), "conjugate_gradient");
  j = solver_scene();
  j["simulation"]["collision_friction"] = -0.5;
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.collision_friction: expected a number ≥ 0, got -0.5");
  j["simulation"]["collision_friction"] = "0.5 m";
  EXPECT_CONTAINS(scene_error_of(j), "scene.json: simulation.collision_friction: expected a number");
}

TEST(SolverScene, UnknownOrMisplacedKeysInConstraints) {
  Json j = solver_scene();
  j["simulation"]["constraints"]["tolerence"] = 1e-3;
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.tolerence: unknown key; did you mean "
            "'tolerance'? (known keys here: method, edges, tolerance, max_iterations, "
            "max_stretch, reuse_iterations)");
  j = solver_scene();
  j["simulation"]["constraints"] = {{"metod", "pairwise"}, {"max_stretch", 0.1}};
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: simulation.constraints.metod: unknown key; did you mean 'method'?");
  j = solver_scene();
  j["simulation"]["constraints"] = "fast_projection";
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: simulation.constraints: expected an object, got the string");
  j = solver_scene();
  j["simulation"]["constraint"] = j["simulation"]["constraints"];
  j["simulation"].erase("constraints");
  EXPECT_CONTAINS(scene_error_of(j),
                  "scene.json: simulation.constraint: unknown key; did you mean 'constraints'?");
  // A key the method does not use is an error, not silently ignored.
  j = solver_scene();
  j["simulation"]["constraints"]["max_stretch"] = 0.05;
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.max_stretch: expected only with method "
            "'pairwise' (it has no effect otherwise), got method 'fast_projection'");
  j["simulation"]["constraints"] = {{"tolerance", 1e-3}};  // method defaults to 'none'
  EXPECT_EQ(scene_error_of(j),
            "scene.json: simulation.constraints.tolerance: expected only with method "
            "'fast_projection' or 'pairwise' (it has no effect otherwise), got method 'none'");
}

// The parsed settings build a simulator that runs: implicit Euler, a projection through the
// chosen back-end, friction against the plane.
TEST(SolverScene, ParsedSettingsDriveTheSimulator) {
  for (const char* method : {"fast_projection", "pairwise"}) {
    Json j = solver_scene();
    j["simulation"]["constraints"] = {{"method", method}, {"tolerance", 1e-2}};
    const Scene scene = parse_json_scene(j);
    const sim::ClothMesh mesh = sim::make_grid(scene.grid);
    sim::Simulator simulator(mesh, scene.material, sim::resolve_pins(scene.pins, mesh), scene.sim);
    EXPECT_NO_THROW(simulator.advance(0.1)) << method;
    const sim::StepStatistics stats = simulator.take_step_statistics();
    EXPECT_GT(stats.steps, 0);
    EXPECT_GT(stats.projection_iterations, 0) << method;
    EXPECT_EQ(stats.failed_implicit_solves, 0) << method;
  }
}

}  // namespace
}  // namespace weft::app
