// WEFT_CHECK: a broken invariant throws base::InternalError (not std::invalid_argument, which is
// bad input) naming the file, the line and the condition; a kept one costs nothing visible.

#include "base/check.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace weft::base {
namespace {

TEST(WeftCheck, PassingCheckDoesNothing) {
  int evaluated = 0;
  WEFT_CHECK(++evaluated == 1, "never built");
  EXPECT_EQ(evaluated, 1);  // the condition is evaluated once
}

TEST(WeftCheck, FailureThrowsInternalErrorWithFileLineAndCondition) {
  const int line = __LINE__ + 2;
  try {
    WEFT_CHECK(1 + 1 == 3, "arithmetic is " + std::string("broken"));
    FAIL() << "no exception";
  } catch (const InternalError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("check_test.cpp:" + std::to_string(line) + ":"), std::string::npos)
        << message;
    EXPECT_NE(message.find("1 + 1 == 3"), std::string::npos) << message;
    EXPECT_NE(message.find("arithmetic is broken"), std::string::npos) << message;
    EXPECT_NE(e.file().find("check_test.cpp"), std::string::npos);
    EXPECT_EQ(e.line(), line);
  }
}

TEST(WeftCheck, InternalErrorIsNotABadInputError) {
  const auto fails = [] { WEFT_CHECK(false, ""); };
  EXPECT_THROW(fails(), std::logic_error);
  bool caught_as_bad_input = false;
  try {
    fails();
  } catch (const std::invalid_argument&) {
    caught_as_bad_input = true;
  } catch (const InternalError&) {
  }
  EXPECT_FALSE(caught_as_bad_input);
}

}  // namespace
}  // namespace weft::base
