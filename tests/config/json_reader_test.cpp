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

TEST_CASE("KeySpecRecorder notes each key of its file with type, default and range", "[config]") {
  const json j = json::parse(R"({"p": "1 kPa", "sub": {"n": 3}})");
  KeySpecRecorder recorder("scene.json");
  JsonReader r(j, "scene.json");
  r.quantity("p", Dimension::pressure, std::nullopt, 0.0, 1e3);
  r.quantity("t", Dimension::length, 0.65, 1e-6, 100);
  r.choice("kind", {"a", "b"}, std::string("b"));
  JsonReader sub = r.object("sub");
  sub.integer("n", 4, 1, 2147483647);
  sub.number("x", 2.5, 0.0, 1e12);
  sub.document("x", "", "twice n");
  const json preset = json::object();
  JsonReader other(preset, "preset.json");
  other.number("ignored", 1.0);
  const auto& keys = recorder.keys();
  REQUIRE(keys.size() == 5);
  CHECK(keys[0].path == "p");
  CHECK(keys[0].type == "pressure");
  CHECK(keys[0].default_value == "required");
  CHECK(keys[0].range == "[0 MPa, 1000 MPa]");
  CHECK(keys[1].default_value == "0.65 mm");  // an internal default shown in the internal unit
  CHECK(keys[1].range == "[1e-6 mm, 100 mm]");
  CHECK(keys[2].type == "one of a|b");
  CHECK(keys[2].default_value == "b");
  CHECK(keys[3].path == "sub.n");
  CHECK(keys[3].range == "≥ 1");
  CHECK(keys[4].default_value == "twice n");  // document() overrides the reading call's note
  CHECK(keys[4].range == "[0, 1e12]");
  CHECK(r.used()["t"] == "0.65 mm");
}
