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
