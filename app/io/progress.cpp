#include "app/io/progress.h"

#include <unistd.h>

#include <cmath>

namespace weft::app {

std::string format_duration(double seconds) {
  char text[64];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else {
    const long s = std::lround(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  }
  return text;
}

Progress::Progress(std::FILE* stream, int total, std::string label)
    : m_stream(stream), m_total(total), m_label(std::move(label)),
      m_terminal(isatty(fileno(stream)) != 0) {}

double Progress::elapsed_s() const {
  return m_watch.seconds();
}

void Progress::update(int done, const std::string& detail) {
  const double elapsed = elapsed_s();
  update(done, detail, done > 0 ? elapsed * (m_total - done) / done : 0.0);
}

void Progress::update(int done, const std::string& detail, double eta) {
  const double elapsed = elapsed_s();
  const std::string times =
      "elapsed " + format_duration(elapsed) +
      (done < m_total ? ", ETA " + (eta >= 0.0 ? format_duration(eta) : std::string("?")) : "");
  if (m_terminal) {
    constexpr int width = 30;
    const int filled = m_total > 0 ? width * done / m_total : width;
    const std::string bar = std::string(filled, '#') + std::string(width - filled, '.');
    std::fprintf(m_stream, "\r\033[K%s [%s] %d/%d  %s  %s", m_label.c_str(), bar.c_str(), done,
                 m_total, detail.c_str(), times.c_str());
    std::fflush(m_stream);
    return;
  }
  // Plain lines, at most one a second, and always the last.
  if (done < m_total && elapsed - m_last_line_s < 1.0) return;
  m_last_line_s = elapsed;
  std::fprintf(m_stream, "%s %d/%d  %s  %s\n", m_label.c_str(), done, m_total, detail.c_str(),
               times.c_str());
  std::fflush(m_stream);
}

void Progress::finish() {
  if (m_terminal) std::fprintf(m_stream, "\n");
  std::fflush(m_stream);
}

}  // namespace weft::app
