// Material presets and a preset with overrides ("base"): the one overridden value changes,
// every other value is the preset's, and a bad base is an InputError naming the key.
#include <catch2/catch.hpp>

#include "valve/config/material_config.hpp"
#include "valve/core/error.hpp"

using namespace valve;

TEST_CASE("a material based on a preset overrides only the keys it names", "[config]") {
  const MaterialConfig preset = load_material(json("mitral_leaflet_table51"), "scene.json", "material", ".", nullptr);
  const json patched = {{"base", "mitral_leaflet_table51"},
                        {"bilinear", {{"fiber", {{"m1", "0.01155 MPa"}}}}},
                        {"thickness", "0.95 mm"}};
  json used;
  const MaterialConfig m = load_material(patched, "scene.json", "material", ".", &used);
  // Table 5.1: fiber m1 0.011 MPa, +5 %; everything else as in the preset.
  CHECK(m.bilinear().fiber.m1 == Approx(0.01155).epsilon(1e-12));
  CHECK(m.bilinear().fiber.m2 == Approx(2.3).epsilon(1e-12));
  CHECK(m.bilinear().fiber.lambda_star == Approx(1.13).epsilon(1e-12));
  CHECK(m.bilinear().cross.m1 == Approx(0.0033).epsilon(1e-12));
  CHECK(m.bilinear().cross.m2 == Approx(0.76).epsilon(1e-12));
  CHECK(m.bilinear().cross.lambda_star == Approx(1.33).epsilon(1e-12));
  CHECK(*m.thickness == Approx(0.95));
  CHECK(*preset.thickness == Approx(1.0));
  CHECK(m.fung->c == Approx(preset.fung->c));
  CHECK(used["base"].get<std::string>().find("mitral_leaflet_table51.json") != std::string::npos);

  CHECK_THROWS_AS(load_material(json{{"base", "no_such_preset"}}, "scene.json", "material", ".", nullptr), InputError);
  CHECK_THROWS_WITH(load_material(json{{"base", 3}}, "scene.json", "material", ".", nullptr),
                    Catch::Contains("material.base") && Catch::Contains("preset"));
}

TEST_CASE("the Texas TriValve presets load as HGO laws with the deck's values", "[config][material]") {
  // Healthy_QuasiStatic.inp, VUANISO_ISO_Septal_Leaflet: 0.001000, 20.066890, 0.000191, 17.751490.
  const MaterialConfig m = load_material(json("ttv_septal"), "scene.json", "material", ".", nullptr);
  REQUIRE(m.hgo);
  CHECK_FALSE(m.fung);
  CHECK(m.hgo->C10 == Approx(0.001));
  CHECK(m.hgo->C01 == Approx(20.06689));
  CHECK(m.hgo->k1 == Approx(0.000191));
  CHECK(m.hgo->k2 == Approx(17.75149));
  CHECK(*m.thickness == Approx(0.65));
  CHECK(m.law()->name() == "hgo");
  // The mass-spring curves are fitted from the same law: the fibers are the stiffer direction
  // at the top of the fit.
  const BilinearParameters b = m.bilinear();
  CHECK(b.fiber.m2 > b.cross.m2);
  CHECK_THROWS_WITH(load_material(json{{"law", "hgo"}, {"C10", "1 kPa"}}, "scene.json", "material", ".", nullptr),
                    Catch::Contains("C01"));
}
