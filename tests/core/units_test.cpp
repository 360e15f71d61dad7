#include <catch2/catch.hpp>

#include "valve/core/error.hpp"
#include "valve/core/units.hpp"

using namespace valve;

TEST_CASE("quantities convert to the internal mm-g-ms system", "[core]") {
  CHECK(parse_quantity("80 mmHg", Dimension::pressure, "k") == Approx(80 * 133.322387415e-6));
  CHECK(parse_quantity("16 kPa", Dimension::pressure, "k") == Approx(0.016));
  CHECK(parse_quantity("2.3 MPa", Dimension::pressure, "k") == Approx(2.3));
  CHECK(parse_quantity("9.7 Pa", Dimension::pressure, "k") == Approx(9.7e-6));
  CHECK(parse_quantity("0.5 mm", Dimension::length, "k") == Approx(0.5));
  CHECK(parse_quantity("1e-5 m", Dimension::length, "k") == Approx(0.01));
  CHECK(parse_quantity("1060 kg/m^3", Dimension::density, "k") == Approx(1.06e-3));
  CHECK(parse_quantity("10 N/m", Dimension::stiffness, "k") == Approx(0.01));
  CHECK(parse_quantity(" 2 s ", Dimension::time, "k") == Approx(2000));
}

TEST_CASE("ambiguous or wrong units are rejected with the key named", "[core]") {
  CHECK_THROWS_WITH(parse_quantity("80", Dimension::pressure, "scene.json: pressure.value"),
                    Catch::Contains("scene.json: pressure.value") && Catch::Contains("bare number"));
  CHECK_THROWS_AS(parse_quantity("80 mm", Dimension::pressure, "k"), InputError);
  CHECK_THROWS_AS(parse_quantity("abc kPa", Dimension::pressure, "k"), InputError);
  CHECK_THROWS_AS(parse_quantity("nan kPa", Dimension::pressure, "k"), InputError);
}

TEST_CASE("format_quantity writes internal values that parse back exactly", "[core]") {
  CHECK(format_quantity(0.65, Dimension::length) == "0.65 mm");
  CHECK(format_quantity(1.06e-3, Dimension::density) == "0.00106 g/mm^3");
  for (const double x : {0.1, 1.0 / 3.0, 2.5e-7, 1e12}) {
    CHECK(parse_quantity(format_quantity(x, Dimension::pressure), Dimension::pressure, "k") == x);
    CHECK(parse_quantity(format_quantity(x, Dimension::density), Dimension::density, "k") == x);
  }
}
