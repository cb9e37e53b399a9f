// A sweep point's result files (see sweep_point.h).

#include "app/sweep/sweep_point.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "app/io/npy_file.h"
#include "app/io/output_files.h"
#include "sim/simulator.h"

namespace weft::app {

namespace fs = std::filesystem;

namespace {

fs::path positions_file(const fs::path& dir, std::size_t k) {
  return dir / "points" / ("run_" + std::to_string(k) + ".npy");
}

std::string exact(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

fs::path sweep_point_file(const fs::path& dir, std::size_t k) {
  return dir / "points" / ("run_" + std::to_string(k) + ".txt");
}

void write_sweep_point(const fs::path& dir, std::size_t k, const SweepRun& run) {
  fs::create_directories(dir / "points");
  if (!run.diverged)  // a diverged run's last state may not be finite, and is not compared
    write_npy_points(positions_file(dir, k), run.x);
  std::ostringstream text;
  text << "weft sweep point\n"
       << "run: " << k << "\n"
       << "settings: " << one_line(describe(run.settings)) << "\n"
       << "wall_time_s: " << exact(run.wall_s) << "\n"
       << "steps: " << run.steps << "\n"
       << "time_step_s: " << exact(run.time_step_s) << "\n"
       << "max_strain: " << exact(run.max_strain) << "\n"
       << "diverged: " << run.diverged << "\n"
       << "failure: " << one_line(run.failure) << "\n";
  write_text(sweep_point_file(dir, k), text.str());
}

void read_sweep_point(const fs::path& dir, std::size_t k, SweepRun& run) {
  const fs::path path = sweep_point_file(dir, k);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": no result (its task did not finish)");
  std::map<std::string, std::string> fields;
  std::string line;
  std::getline(in, line);
  if (line != "weft sweep point")
    throw std::runtime_error(path.string() + ": not a weft sweep point's result");
  while (std::getline(in, line)) {
    const std::size_t colon = line.find(": ");
    if (colon != std::string::npos) fields[line.substr(0, colon)] = line.substr(colon + 2);
  }
  const auto field = [&](const std::string& key) {
    const auto it = fields.find(key);
    if (it == fields.end()) throw std::runtime_error(path.string() + ": no '" + key + "' (damaged)");
    return it->second;
  };
  const auto number = [&](const std::string& key) {
    const std::string text = field(key);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0')
      throw std::runtime_error(path.string() + ": '" + key + "' is not a number: " + text);
    return v;
  };
  if (field("run") != std::to_string(k) || field("settings") != one_line(describe(run.settings)))
    throw std::runtime_error(path.string() + ": the result of another sweep (run " + field("run") +
                             ", " + field("settings") + "; expected run " + std::to_string(k) +
                             ", " + describe(run.settings) + ")");
  run.wall_s = number("wall_time_s");
  run.steps = static_cast<long>(number("steps"));
  run.time_step_s = number("time_step_s");
  run.max_strain = number("max_strain");
  run.diverged = field("diverged") == "1";
  run.failure = fields["failure"];
  run.mesh = make_simulator(run.scene)->mesh();
  if (!run.diverged) {
    run.x = read_npy_points(positions_file(dir, k));
    if (run.x.rows() != run.mesh.vertex_count())
      throw std::runtime_error(positions_file(dir, k).string() + ": " +
                               std::to_string(run.x.rows()) + " vertices, the scene's cloth has " +
                               std::to_string(run.mesh.vertex_count()));
  }
}

}  // namespace weft::app
