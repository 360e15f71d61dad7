// Command-line switches (--quiet, --quiet=false) and the atomic writer's temporary files.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "valve/core/atomic_file.hpp"
#include "valve/core/cli.hpp"
#include "valve/core/error.hpp"

using namespace valve;

namespace {
CommandLine parse(std::vector<std::string> words) {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  return CommandLine(static_cast<int>(argv.size()), argv.data(), {"out"}, {"quiet"});
}
}  // namespace

TEST_CASE("a switch is on bare or =true, off with =false; anything else is refused", "[core][cli]") {
  CHECK(parse({"stage", "--quiet"}).has("quiet"));
  CHECK(parse({"stage", "--quiet=true"}).has("quiet"));
  CHECK_FALSE(parse({"stage", "--quiet=false"}).has("quiet"));
  CHECK_FALSE(parse({"stage", "--quiet=0"}).has("quiet"));
  CHECK_FALSE(parse({"stage"}).has("quiet"));
  CHECK_FALSE(parse({"stage", "--quiet", "--quiet=off"}).has("quiet"));  // the last one counts
  CHECK_THROWS_WITH(parse({"stage", "--quiet=maybe"}), Catch::Contains("--quiet") && Catch::Contains("true or false"));
  CHECK(parse({"stage", "--out", "dir"}).has("out"));
}

TEST_CASE("an atomic write leaves the whole file and no temporary beside it", "[core][atomic_file]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "valve_atomic_file_test";
  fs::remove_all(dir);
  write_file_atomic(dir / "a.json", "{\"x\": 1}\n");
  write_file_atomic(dir / "a.json", "{\"x\": 2}\n");  // replaces it
  CHECK(read_text_file(dir / "a.json") == "{\"x\": 2}\n");
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++entries;
    CHECK(e.path().filename() == "a.json");
  }
  CHECK(entries == 1);
  // A writer that fails leaves nothing: neither the file nor its temporary.
  CHECK_THROWS(write_via_temp(dir / "b.vtp", [](const fs::path&) { throw Error("no"); }));
  entries = 0;
  for (auto it = fs::directory_iterator(dir); it != fs::directory_iterator(); ++it) ++entries;
  CHECK(entries == 1);
  fs::remove_all(dir);
}

TEST_CASE("a numeric flag is a plain decimal in range, or the fallback when absent", "[core][cli]") {
  auto flags = [](std::vector<std::string> words) {
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    return CommandLine(static_cast<int>(argv.size()), argv.data(), {"n"}, {});
  };
  CHECK(number_flag(flags({"stage"}), "n", 7.5, 0, 10) == 7.5);
  CHECK(number_flag(flags({"stage", "--n", "2.25"}), "n", 0, 0, 10) == 2.25);
  CHECK(number_flag(flags({"stage", "--n", "-1e-3"}), "n", 0, -1, 1) == -0.001);
  for (const char* bad : {"0x2", "inf", "nan", "2abc", "", "11"})
    CHECK_THROWS_WITH(number_flag(flags({"stage", "--n", bad}), "n", 0, 0, 10),
                      std::string("--n: expected a number in [0, 10], found \"") + bad + "\"");
  CHECK(whole_number_flag(flags({"stage", "--n", "12"}), "n", 1, 0, 100) == 12);
  CHECK(whole_number_flag(flags({"stage"}), "n", 3, 0, 100) == 3);
  CHECK_THROWS_WITH(whole_number_flag(flags({"stage", "--n", "12.5"}), "n", 1, 0, 100),
                    "--n: expected a whole number in [0, 100], found \"12.5\"");
  CHECK_THROWS_WITH(whole_number_flag(flags({"stage", "--n", "lots"}), "n", 1, 0, 100),
                    "--n: expected a number in [0, 100], found \"lots\"");
}
