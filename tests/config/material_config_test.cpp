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

TEST_CASE("the Texas TriValve presets load as the deck's isotropic exponential law", "[config][material]") {
  // Healthy_QuasiStatic.inp, VUANISO_ISO_Septal_Leaflet: 0.001000, 20.066890, 0.000191, 17.751490,
  // the property order (C0, D, C1, C2) of Leaflet_Material.f's VUANISOHYPER_ISO.
  const MaterialConfig m = load_material(json("ttv_septal"), "scene.json", "material", ".", nullptr);
  REQUIRE(m.iso_exponential);
  CHECK_FALSE(m.fung);
  CHECK_FALSE(m.hgo);
  CHECK(m.iso_exponential->C0 == Approx(0.001));
  CHECK(m.iso_exponential->D == Approx(20.06689));
  CHECK(m.iso_exponential->C1 == Approx(0.000191));
  CHECK(m.iso_exponential->C2 == Approx(17.75149));
  CHECK_FALSE(m.compressible);
  CHECK(*m.thickness == Approx(0.65));
  CHECK(m.law()->name() == "iso_exponential");
  CHECK(m.source.find("0.001000, 20.066890, 0.000191, 17.751490") != std::string::npos);
  // An isotropic law fits the same mass-spring curve in both directions.
  const BilinearParameters b = m.bilinear();
  CHECK(b.fiber.m2 == Approx(b.cross.m2).epsilon(1e-9));
  CHECK(b.fiber.lambda_star == Approx(b.cross.lambda_star).epsilon(1e-9));
  // "compressible": true keeps the deck's (J - 1)²/D term.
  const MaterialConfig c =
      load_material(json{{"base", "ttv_septal"}, {"compressible", true}}, "scene.json", "material", ".", nullptr);
  CHECK(c.law()->name() == "iso_exponential_compressible");
}

TEST_CASE("the modified HGO law reads the subroutine's names; bad values are refused", "[config][material]") {
  const MaterialConfig m = load_material(json{{"law", "hgo"}, {"C10", "2 kPa"}, {"D", "10 1/MPa"}, {"k1", "0.3 kPa"},
                                              {"k2", 12}, {"kappa", 0.05}, {"C01", 15}},
                                         "scene.json", "material", ".", nullptr);
  REQUIRE(m.hgo);
  CHECK(m.hgo->C10 == Approx(0.002));
  CHECK(m.hgo->D == Approx(10));
  CHECK(m.hgo->k1 == Approx(0.0003));
  CHECK(m.hgo->kappa == Approx(0.05));
  CHECK(m.law()->name() == "hgo");
  CHECK_THROWS_WITH(load_material(json{{"law", "hgo"}, {"C10", "1 kPa"}}, "scene.json", "material", ".", nullptr),
                    Catch::Contains("C01"));
  CHECK_THROWS_WITH(load_material(json{{"law", "iso_exponential"}, {"C0", "1 kPa"}, {"compressible", true}}, "scene.json",
                                  "material", ".", nullptr),
                    Catch::Contains("material.D") && Catch::Contains("D > 0"));
  CHECK_THROWS_WITH(load_material(json{{"law", "iso_exponential"}, {"C0", "1 kPa"}, {"D", 20}}, "scene.json", "material",
                                  ".", nullptr),
                    Catch::Contains("material.D") && Catch::Contains("1/MPa"));
}

TEST_CASE("chord laws: linear and Ogden, with units; bad ones are refused", "[config][chordae]") {
  // JsonReader keeps a reference: each object outlives its reader.
  const json linear{{"law", "linear"}, {"youngs_modulus", "40 MPa"}};
  JsonReader r1(linear, "c.json", "materials.A");
  CHECK(parse_rod_law(r1)->response(1.1).nominal_stress == Approx(4.0));
  const json neo_hookean{{"law", "ogden"}, {"mu", {"0.5 MPa"}}, {"alpha", {2}}};
  JsonReader r2(neo_hookean, "c.json", "materials.A");
  CHECK(parse_rod_law(r2)->response(1.2).nominal_stress == Approx(0.5 * (1.2 - 1 / 1.44)));  // μ(λ − λ⁻²)
  const json bad_alpha{{"law", "ogden"}, {"mu", {"0.5 MPa", "1 MPa"}}, {"alpha", {2}}};
  JsonReader r3(bad_alpha, "c.json", "materials.A");
  CHECK_THROWS_WITH(parse_rod_law(r3), Catch::Contains("materials.A.alpha") && Catch::Contains("2 numbers"));
  const json unitless{{"law", "ogden"}, {"mu", {0.5}}, {"alpha", {2}}};
  JsonReader r4(unitless, "c.json", "materials.A");
  CHECK_THROWS_WITH(parse_rod_law(r4), Catch::Contains("materials.A.mu[0]"));
  const json unstable{{"law", "ogden"}, {"mu", {"-0.5 MPa"}}, {"alpha", {2}}};
  JsonReader r5(unstable, "c.json", "materials.A");
  CHECK_THROWS_WITH(parse_rod_law(r5), Catch::Contains("one sign"));
}
