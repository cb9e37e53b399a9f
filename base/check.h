#pragma once
// WEFT_CHECK(condition, message): an internal invariant, kept in release builds. A failure is a
// bug in weft, not bad input, and throws weft::base::InternalError ("file:line: check
// `condition` failed: message"), which no handler of user errors catches: bad input throws
// std::invalid_argument (or an error type of its own) and names the file, key or item instead.

#include <stdexcept>
#include <string>

namespace weft::base {

// A broken internal invariant: a bug. Deliberately not a std::invalid_argument.
class InternalError : public std::logic_error {
 public:
  InternalError(const char* file, int line, const char* condition, const std::string& message);
  const std::string& file() const { return m_file; }
  int line() const { return m_line; }

 private:
  std::string m_file;
  int m_line;
};

namespace detail {
[[noreturn]] void check_failed(const char* file, int line, const char* condition,
                               const std::string& message);
}  // namespace detail

}  // namespace weft::base

// The message is built only when the check fails.
#define WEFT_CHECK(condition, message)                                                   \
  do {                                                                                   \
    if (!(condition))                                                                    \
      ::weft::base::detail::check_failed(__FILE__, __LINE__, #condition, (message));     \
  } while (false)
