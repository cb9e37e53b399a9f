#include "app/io/stats_csv.h"

#include <sstream>

#include "app/io/output_files.h"

namespace weft::app {

namespace {

// The header line.
constexpr const char* header =
    "frame,time_s,sim_ms,render_ms,steps,max_strain,mean_strain,kinetic_energy_J,"
    "elastic_energy_J,gravity_energy_J,max_speed_m_s,projection_iterations,"
    "max_step_iterations,unconverged_steps,solve_ms,failed_implicit_solves,cg_iterations,"
    "min_step_ms,max_step_ms,rejected_steps,vertices,remeshes,remesh_energy_J,"
    "remesh_indicator_m,remesh_excess,coarsenings,self_intersections,max_self_contacts\n";

std::string row_text(const FrameStats& r) {
  const auto& d = r.diagnostics;
  std::ostringstream line;
  line.precision(9);
  const auto& s = r.steps;
  line << r.frame << ',' << d.time_s << ',' << r.sim_ms << ',' << r.render_ms << ',' << s.steps
        << ',' << d.max_strain << ',' << d.mean_strain << ',' << d.kinetic_energy_J << ','
        << d.elastic_energy_J << ',' << d.gravity_energy_J << ',' << d.max_speed_m_s << ','
        << s.projection_iterations << ',' << s.max_projection_iterations << ','
        << s.unconverged_steps << ',' << 1e3 * s.solve_s << ',' << s.failed_implicit_solves << ','
        << s.cg_iterations << ',' << 1e3 * s.min_step_s << ',' << 1e3 * s.max_step_s << ','
        << s.rejected_steps << ',' << r.vertices << ',' << s.remeshes << ',' << s.remesh_energy_J
        << ',' << s.max_remesh_indicator_m << ',' << s.max_remesh_excess << ',' << s.coarsenings
        << ',' << r.self_intersections << ',' << s.max_self_contacts << '\n';
  return line.str();
}

}  // namespace

StatsCsv::StatsCsv(const std::filesystem::path& path) : m_path(path), m_text(header) {}

void StatsCsv::write(const FrameStats& r) {
  m_text += row_text(r);
  write_text(m_path, m_text);
}

void StatsCsv::restore(const std::vector<FrameStats>& rows) {
  for (const FrameStats& r : rows) m_text += row_text(r);
}

void StatsCsv::rewrite(const std::vector<FrameStats>& rows) {
  m_text = header;
  restore(rows);
  write_text(m_path, m_text);
}

}  // namespace weft::app
