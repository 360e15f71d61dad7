#include <catch2/catch.hpp>

#include "valve/config/json_reader.hpp"
#include "valve/core/error.hpp"

using namespace valve;

TEST_CASE("JsonReader fills defaults, records them and rejects unknown keys", "[config]") {
  const json j = json::parse(R"({"a": 2, "p": "10 kPa", "sub": {"b": true}, "typo": 1})");
  JsonReader r(j, "f.json");
  CHECK(r.number("a", 1.0) == 2.0);
  CHECK(r.number("missing", 5.0) == 5.0);
  CHECK(r.quantity("p", Dimension::pressure) == Approx(0.01));
  JsonReader s = r.object("sub");
  CHECK(s.boolean("b"));
  r.record("sub", s.finish());
  CHECK(r.used()["missing"] == 5.0);
  CHECK_THROWS_WITH(r.finish(), Catch::Contains("f.json: typo") && Catch::Contains("unknown key"));
}

TEST_CASE("JsonReader errors name file, key, expected and found", "[config]") {
  const json j = json::parse(R"({"a": "x", "n": -1, "c": "maybe", "q": 3})");
  JsonReader r(j, "s.json", "solver");
  CHECK_THROWS_WITH(r.number("a"), Catch::Contains("s.json: solver.a: expected a number, found string"));
  CHECK_THROWS_WITH(r.number("n", std::nullopt, 0.0), Catch::Contains("solver.n"));
  CHECK_THROWS_WITH(r.choice("c", {"yes", "no"}), Catch::Contains("one of yes|no"));
  CHECK_THROWS_WITH(r.quantity("q", Dimension::pressure), Catch::Contains("with a unit"));
  CHECK_THROWS_WITH(r.number("absent"), Catch::Contains("required"));
}
