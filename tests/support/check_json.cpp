// check_json FILE KEY.PATH MIN MAX [KEY.PATH MIN MAX ...]
// Exits 0 if every number at the (dot-separated, array indices allowed) paths lies in
// [MIN, MAX] (booleans count as 1 and 0); prints each value. Used by stage and pipeline tests to assert tolerances.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

int main(int argc, char** argv) {
  if (argc < 5 || (argc - 2) % 3 != 0) {
    std::fprintf(stderr, "usage: check_json FILE PATH MIN MAX [PATH MIN MAX ...]\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::fprintf(stderr, "check_json: cannot read %s\n", argv[1]);
    return 2;
  }
  nlohmann::json j = nlohmann::json::parse(in);
  int failures = 0;
  for (int k = 2; k + 2 < argc; k += 3) {
    const nlohmann::json* v = &j;
    std::stringstream path(argv[k]);
    std::string part;
    while (std::getline(path, part, '.')) {
      if (v->is_array()) v = &(*v)[std::stoul(part)];
      else if (v->contains(part)) v = &(*v)[part];
      else {
        std::fprintf(stderr, "check_json: %s: no key %s\n", argv[k], part.c_str());
        return 1;
      }
    }
    const double lo = std::stod(argv[k + 1]), hi = std::stod(argv[k + 2]);
    nlohmann::json as_number;
    if (v->is_boolean()) as_number = v->get<bool>() ? 1 : 0, v = &as_number;
    if (!v->is_number()) {
      std::fprintf(stderr, "check_json: %s is not a number: %s\n", argv[k], v->dump().c_str());
      ++failures;
      continue;
    }
    const double x = v->get<double>();
    const bool ok = x >= lo && x <= hi;
    std::printf("%s %s = %.6g (expected [%g, %g])\n", ok ? "ok  " : "FAIL", argv[k], x, lo, hi);
    failures += !ok;
  }
  return failures ? 1 : 0;
}
