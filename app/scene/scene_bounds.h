#pragma once
// What a scene's numbers must allow for its run to be computed at all, checked once the cloth
// is made (make_simulator), before anything is written: energies within what a double holds, and
// a remeshed cloth that fits in its vertex limit at its finest edge. Each check throws InputError
// naming the scene file and the key (docs/reliability.md).

#include "app/scene/scene.h"
#include "sim/simulator.h"

namespace weft::app {

// The largest energy scale, in joules, a scene may reach with its cloth's mass, gravity, speed
// and strain limits and stiffnesses: 1000 times below a double's largest (1.8e308), so that the
// sums of stats.csv (kinetic + elastic + gravity) and the energy guard's margins stay finite (a
// density of 1.7e308 kg/m^2 used to write gravity_energy_J = inf). No fabric comes near: 1e300
// kg/m^2 on the 20 cm test cloth is 8e302 J.
inline constexpr double max_energy_scale_J = 1e305;

// Throws InputError naming cloth.material.density (with simulation.gravity) or the stiffness
// key when M (|g| R + ½ v_max²) or ½ k A s_max² passes max_energy_scale_J (M the cloth's mass,
// R its farthest vertex from the origin plus its diagonal, v_max simulation.max_speed, k its
// largest in-plane stiffness, A its area, s_max simulation.max_strain); and naming
// simulation.remesh.h_min when a uniform mesh at h_min over the cloth's area would have more
// vertices than simulation.remesh.max_vertices (h_min 1 µm used to refine for 144 s before
// failing).
void check_scene_bounds(const Scene& scene, const sim::Simulator& simulator);

// The largest simulation.remesh.max_vertices a scene may give.
inline constexpr long max_remesh_vertices = 2'000'000;

// The vertices of a mesh of equilateral triangles of edge h_m over area_m2 (one vertex per
// √3/2 h² of area): the remesher's mesh where all of the cloth is refined to h_min.
double uniform_mesh_vertices(double area_m2, double h_m);

}  // namespace weft::app
