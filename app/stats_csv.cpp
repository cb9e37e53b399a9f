#include "app/stats_csv.h"

#include <stdexcept>

namespace weft::app {

StatsCsv::StatsCsv(const std::filesystem::path& path) : m_path(path), m_out(path) {
  if (!m_out) throw std::runtime_error(path.string() + ": cannot write stats file");
  m_out << "frame,time_s,sim_ms,render_ms,steps,max_strain,kinetic_energy_J,elastic_energy_J,"
           "gravity_energy_J,max_speed_m_s\n";
  m_out.flush();
}

void StatsCsv::write(const FrameStats& r) {
  const auto& d = r.diagnostics;
  m_out.precision(9);
  m_out << r.frame << ',' << d.time_s << ',' << r.sim_ms << ',' << r.render_ms << ',' << r.steps
        << ',' << d.max_strain << ',' << d.kinetic_energy_J << ',' << d.elastic_energy_J << ','
        << d.gravity_energy_J << ',' << d.max_speed_m_s << '\n';
  m_out.flush();
  if (!m_out) throw std::runtime_error(m_path.string() + ": write failed");
}

}  // namespace weft::app
