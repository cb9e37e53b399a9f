#pragma once
// A simulation's state between two steps as bytes, for checkpoints (weft run
// --checkpoint-every, --resume; docs/checkpoints.md): StateWriter appends named sections of
// numbers, vectors and matrices; StateReader reads them back in the same order and throws
// StateArchiveError naming the section when the bytes are not what the reader expects (another
// build's layout, a truncated or edited file). Raw native bytes: a checkpoint is read back by the
// build that wrote it (the checkpoint's header carries a hash of the build), so the doubles come
// back bit for bit.

#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "sim/types.h"

namespace weft::sim {

class StateArchiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateWriter {
 public:
  // Starts a named section; the reader checks the name.
  void section(std::string_view name) { text(std::string(name)); }
  template <class T>
  void pod(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "pod: a trivially copyable value");
    m_bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  template <class T>
  void pods(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "pods: trivially copyable values");
    pod(static_cast<std::uint64_t>(values.size()));
    m_bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void text(const std::string& value) {
    pod(static_cast<std::uint64_t>(value.size()));
    m_bytes += value;
  }
  template <class Derived>
  void matrix(const Eigen::PlainObjectBase<Derived>& m) {
    pod(static_cast<std::int64_t>(m.rows()));
    pod(static_cast<std::int64_t>(m.cols()));
    m_bytes.append(reinterpret_cast<const char*>(m.data()),
                   static_cast<std::size_t>(m.size()) * sizeof(typename Derived::Scalar));
  }
  const std::string& bytes() const { return m_bytes; }

 private:
  std::string m_bytes;
};

class StateReader {
 public:
  // `bytes` must outlive the reader; `what` names them in errors (e.g. the checkpoint's path).
  StateReader(std::string_view bytes, std::string what) : m_bytes(bytes), m_what(std::move(what)) {}

  // Throws unless the next section is `name`.
  void section(std::string_view name) {
    m_section = std::string(name);
    const std::string found = text();
    if (found != name)
      fail("expected the section '" + std::string(name) + "', found '" + found.substr(0, 40) + "'");
  }
  template <class T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>, "pod: a trivially copyable value");
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  template <class T>
  void pod(T& value) { value = pod<T>(); }
  template <class T>
  void pods(std::vector<T>& values) {
    const auto n = count(sizeof(T));
    values.resize(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  std::string text() {
    const auto n = count(1);
    return std::string(take(n), n);
  }
  // Reads a matrix; `rows` and `cols` (−1: any) are what the reader's simulation has.
  template <class Derived>
  void matrix(Eigen::PlainObjectBase<Derived>& m, Eigen::Index rows = -1, Eigen::Index cols = -1) {
    const auto r = pod<std::int64_t>(), c = pod<std::int64_t>();
    if (r < 0 || c < 0 || (rows >= 0 && r != rows) || (cols >= 0 && c != cols))
      fail("a " + std::to_string(r) + "×" + std::to_string(c) + " matrix where the simulation has " +
           std::to_string(rows) + "×" + std::to_string(cols));
    using Scalar = typename Derived::Scalar;
    const std::size_t bytes = static_cast<std::size_t>(r * c) * sizeof(Scalar);
    if (bytes > left()) fail("truncated");
    m.resize(r, c);
    if (bytes > 0) std::memcpy(m.data(), take(bytes), bytes);
  }
  bool at_end() const { return m_offset == m_bytes.size(); }
  // Throws StateArchiveError: "WHAT: section S: message".
  [[noreturn]] void fail(const std::string& message) const {
    throw StateArchiveError(m_what + ": " + (m_section.empty() ? "" : "section '" + m_section + "': ") +
                            message);
  }

 private:
  std::size_t left() const { return m_bytes.size() - m_offset; }
  const char* take(std::size_t n) {
    if (n > left()) fail("truncated");
    const char* p = m_bytes.data() + m_offset;
    m_offset += n;
    return p;
  }
  std::size_t count(std::size_t element_size) {
    const auto n = pod<std::uint64_t>();
    if (element_size > 0 && n > left() / element_size) fail("truncated");
    return static_cast<std::size_t>(n);
  }

  std::string_view m_bytes;
  std::size_t m_offset = 0;
  std::string m_what;
  std::string m_section;
};

}  // namespace weft::sim
