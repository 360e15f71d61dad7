// A stage's flags made from its config keys, in the order --xml lists them.
#include <catch2/catch.hpp>

#include "valve/core/stage_arguments.hpp"

using namespace valve;

TEST_CASE("stage flags: leading flags, each config key as a flag, trailing flags", "[core][stage_arguments]") {
  CHECK(stage_flags({"out", "config"}, {"name", "gaussian_sigma", "crop_min"}, {"mesh-copies"}) ==
        std::vector<std::string>{"out", "config", "name", "gaussian-sigma", "crop-min", "mesh-copies"});
  CHECK(stage_flags({}, {"min-spur"}) == std::vector<std::string>{"min-spur"});  // already a flag
  CHECK(stage_flags({"out"}, {}).size() == 1);
}
