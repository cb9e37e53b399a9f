#pragma once
// The settings of a static solve (sim/statics/static_equilibrium.h explains each).

namespace weft::sim {

struct StaticSettings {
  double tolerance = 1e-6;        // ‖∇Π‖ / ‖M g‖ over the free vertices
  int max_iterations = 2000;
  double contact_stiffness = 1e3; // k_i = this × m_i |g| / δ
  double imperfection = 1e-3;     // × the mean rest edge length; 0: none
  unsigned seed = 1;
  double max_move = 0.5;          // × the shortest rest edge: the first trust radius
};

}  // namespace weft::sim
