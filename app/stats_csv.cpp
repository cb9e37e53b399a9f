#include "app/stats_csv.h"

#include <stdexcept>

namespace weft::app {

StatsCsv::StatsCsv(const std::filesystem::path& path) : m_path(path), m_out(path) {
  if (!m_out) throw std::runtime_error(path.string() + ": cannot write stats file");
  m_out << "frame,time_s,sim_ms,render_ms,steps,max_strain,mean_strain,kinetic_energy_J,"
           "elastic_energy_J,gravity_energy_J,max_speed_m_s,projection_iterations,"
           "max_step_iterations,unconverged_steps,solve_ms,failed_implicit_solves,cg_iterations,"
           "self_intersections,max_self_contacts\n";
  m_out.flush();
}

void StatsCsv::write(const FrameStats& r) {
  const auto& d = r.diagnostics;
  m_out.precision(9);
  const auto& s = r.steps;
  m_out << r.frame << ',' << d.time_s << ',' << r.sim_ms << ',' << r.render_ms << ',' << s.steps
        << ',' << d.max_strain << ',' << d.mean_strain << ',' << d.kinetic_energy_J << ','
        << d.elastic_energy_J << ',' << d.gravity_energy_J << ',' << d.max_speed_m_s << ','
        << s.projection_iterations << ',' << s.max_projection_iterations << ','
        << s.unconverged_steps << ',' << 1e3 * s.solve_s << ',' << s.failed_implicit_solves << ','
        << s.cg_iterations << ',' << r.self_intersections << ',' << s.max_self_contacts << '\n';
  m_out.flush();
  if (!m_out) throw std::runtime_error(m_path.string() + ": write failed");
}

}  // namespace weft::app
