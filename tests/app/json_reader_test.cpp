#include "app/scene/json_reader.h"

#include <gtest/gtest.h>

#include "app/scene/scene.h"

namespace weft::app {
namespace {

template <class F>
std::string reader_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(JsonReader, RangeText) {
  EXPECT_EQ(Range::gt(0).text(), "> 0");
  EXPECT_EQ(Range::ge(0.5).text(), "≥ 0.5");
  EXPECT_EQ(Range{}.le(3).text(), "≤ 3");
  EXPECT_EQ(Range::gt(0).le(1).text(), "in (0, 1]");
  EXPECT_EQ(Range::closed(2, 4096).text(), "in [2, 4096]");
  EXPECT_EQ(Range::ge(0).lt(180).text(), "in [0, 180)");
  EXPECT_TRUE(Range{}.unbounded());
  EXPECT_TRUE(Range::gt(0).le(1).contains(1.0));
  EXPECT_FALSE(Range::gt(0).le(1).contains(0.0));
  EXPECT_TRUE(Range::closed(0, 1).contains(0.0));
}

TEST(JsonReader, ReadsEachKindAndMarksKeysRead) {
  const Json j = parse_json(R"({"n": 2.5, "i": 7, "f": 3.0, "s": "x", "b": false, "q": "5 cm",
                               "v": [1, 2, 3], "a": "30 deg", "e": "two", "o": {"k": 1},
                               "list": [{"k": 1}, {"k": 2}]})",
                            "t.json");
  ObjectReader r = ObjectReader::root(j, "t.json");
  EXPECT_EQ(r.number("n", required), 2.5);
  EXPECT_EQ(r.integer("i", required, Range{}), 7);
  EXPECT_EQ(r.integer("f", required, Range{}), 3);
  EXPECT_EQ(r.string("s", required), "x");
  EXPECT_FALSE(r.boolean("b", true));
  EXPECT_DOUBLE_EQ(r.quantity("q", Quantity::length, required), 0.05);
  EXPECT_EQ(r.vec3("v", required), Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(r.angle_deg("a", required), 30.0);
  enum class E { one, two };
  constexpr base::EnumNames<E, 2> e_names{{{E::one, "one"}, {E::two, "two"}}};
  EXPECT_EQ(r.enumeration("e", e_names, std::optional<E>(required)), E::two);
  ObjectReader o = r.object("o");
  EXPECT_EQ(o.path(), "o");
  EXPECT_EQ(o.number("k", required), 1.0);
  o.finish();
  const auto list = r.objects("list");
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1].path(), "list[1]");
  // Absent keys take their fallbacks; an absent object reads as empty.
  EXPECT_EQ(r.number("absent", 4.0), 4.0);
  ObjectReader empty = r.object("absent_object");
  EXPECT_EQ(empty.path(), "absent_object");
  EXPECT_EQ(empty.number("x", 1.0), 1.0);
  empty.finish();
  EXPECT_EQ(reader_error_of([&] { r.finish(); }), "no error");  // list[i] need not be finished here
}

TEST(JsonReader, FinishNamesTheFirstUnreadKeyInFileOrder) {
  const Json j = parse_json(R"({"zeta": 1, "alpha": 2, "size": 3})", "t.json");
  ObjectReader r = ObjectReader::root(j, "t.json");
  r.number("size", required);
  r.number("resolution", 2.0);
  EXPECT_EQ(reader_error_of([&] { r.finish(); }),
            "t.json: zeta: unknown key (known keys here: size, resolution)");
  const Json k = parse_json(R"({"a": {"x": 1}})", "t.json");
  ObjectReader top = ObjectReader::root(k, "t.json");
  ObjectReader a = top.object("a");
  EXPECT_EQ(reader_error_of([&] { a.finish(); }), "t.json: a.x: unknown key (no keys are accepted here)");
  ObjectReader b = ObjectReader::root(k, "t.json");
  EXPECT_TRUE(b.has("a"));
  EXPECT_EQ(reader_error_of([&] { b.finish(); }), "t.json: a: this key is not used here");
}

TEST(JsonReader, IntegersMustBeWhole) {
  const Json j =
      parse_json(R"({"a": 3.5, "b": 1e300, "c": 18446744073709551615, "d": true})", "t.json");
  ObjectReader r = ObjectReader::root(j, "t.json");
  EXPECT_EQ(reader_error_of([&] { r.integer("a", required, Range{}); }),
            "t.json: a: expected an integer, got 3.5");
  EXPECT_EQ(reader_error_of([&] { r.integer("b", required, Range{}); }),
            "t.json: b: expected an integer, got 1e+300");
  EXPECT_EQ(reader_error_of([&] { r.integer("c", required, Range{}); }),
            "t.json: c: expected an integer, got 18446744073709551615");
  EXPECT_EQ(reader_error_of([&] { r.integer("d", required, Range::ge(0)); }),
            "t.json: d: expected an integer ≥ 0, got true");
}

TEST(JsonReader, MalformedJsonLineAndColumnCountCharacters) {
  // "é" is two bytes but one column.
  EXPECT_EQ(reader_error_of([] {
              parse_json("{\"a\": 1,\n \"é\": ?}", "u.json");
            }).rfind("u.json:2:7: malformed JSON: syntax error while parsing value", 0),
            0u);
  EXPECT_EQ(reader_error_of([] {
              parse_json("{\"a\": 1} x", "u.json");
            }).rfind("u.json:1:10: malformed JSON:", 0),
            0u);
  EXPECT_EQ(reader_error_of([] { parse_json("{\"a\": [1, {\"b\": 1, \"b\": 2}]}", "u.json"); }),
            "u.json: a[1].b: duplicate key (each key may appear once in an object)");
  EXPECT_EQ(reader_error_of([] { parse_json("[0, 1, 2e400]", "u.json"); }),
            "u.json:1:8: [2]: expected a finite number, got 2e400 (too large for a double)");
}

TEST(JsonReader, FailNamesTheKeyPath) {
  const Json j = parse_json(R"({"a": {"b": 1}})", "f.json");
  ObjectReader r = ObjectReader::root(j, "f.json");
  ObjectReader a = r.object("a");
  EXPECT_EQ(a.path_of("b"), "a.b");
  EXPECT_EQ(reader_error_of([&] { a.fail("b", "expected something else"); }),
            "f.json: a.b: expected something else");
}

}  // namespace
}  // namespace weft::app
