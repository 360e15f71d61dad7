#include "valve/core/slicer_cli.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace valve {

namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string trim(std::string s) {
  s.erase(0, s.find_first_not_of(" \t"));
  s.erase(s.find_last_not_of(" \t") + 1);
  return s;
}

// "--name" as a whole option in `text` (not the start of a longer one, --seed vs --seed-x).
size_t find_option(const std::string& text, const std::string& name) {
  const std::string opt = "--" + name;
  for (size_t at = text.find(opt); at != std::string::npos; at = text.find(opt, at + 1)) {
    const size_t end = at + opt.size();
    if (end == text.size() || !(std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-')) return at;
  }
  return std::string::npos;
}

// The value a synopsis shows after "--name" ("0.15", "gaussian|median|none", "FILE.json").
std::string placeholder(const std::string& synopsis, const std::string& name) {
  const size_t at = find_option(synopsis, name);
  if (at == std::string::npos) return "";
  std::istringstream rest(synopsis.substr(at + name.size() + 2));
  std::string token;
  if (!(rest >> token) || token[0] == '-' || token[0] == '[') return "";
  while (!token.empty() && (token.back() == ']' || token.back() == '.')) token.pop_back();
  return token;
}

std::string identifier(const std::string& flag) {
  std::string id = flag;
  std::replace(id.begin(), id.end(), '-', '_');
  return id;
}

std::string label_of(const std::string& flag) {
  std::string l = flag;
  std::replace(l.begin(), l.end(), '-', ' ');
  if (!l.empty()) l[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(l[0])));
  return l;
}

std::string extension_of(const std::string& token) {
  const size_t dot = token.find('.');
  return dot == std::string::npos ? "" : token.substr(dot);
}

}  // namespace

std::string slicer_cli_xml(const std::string& program, const std::string& usage, const std::vector<std::string>& flags,
                           const std::vector<std::string>& switches) {
  // The synopsis is the first line and the indented lines under it; the prose follows.
  const auto lines = lines_of(usage);
  std::string synopsis, prose;
  size_t k = 0;
  for (; k < lines.size() && (k == 0 || (!lines[k].empty() && lines[k][0] == ' ')); ++k) synopsis += lines[k] + " ";
  const size_t synopsis_lines = k;
  // The options common to every stage (stage_usage.cmake) are Slicer's business, not the user's.
  for (; k < lines.size() && lines[k].rfind("Every stage also takes:", 0) != 0; ++k) prose += trim(lines[k]) + "\n";
  // A one-line explanation of an option: the first prose line naming it.
  auto explained = [&](const std::string& flag, const std::string& shown) {
    for (size_t i = synopsis_lines; i < lines.size(); ++i)
      if (find_option(lines[i], flag) != std::string::npos) return trim(lines[i]);
    return "--" + flag + (shown.empty() ? "" : " " + shown) + " (see --help)";
  };

  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<executable>\n"
    << "  <category>Valve</category>\n"
    << "  <title>" << escape(program) << "</title>\n"
    << "  <description>" << escape(prose) << "</description>\n"
    << "  <version>" << VALVE_VERSION << "</version>\n"
    << "  <documentation-url></documentation-url>\n  <license></license>\n  <contributor>valve</contributor>\n";

  x << "  <parameters>\n    <label>Inputs and outputs</label>\n    <description>Files the stage reads and the folder it writes</description>\n";
  std::istringstream words(synopsis);
  std::string word;
  words >> word;  // the program
  for (int index = 0; words >> word && word[0] != '-' && word[0] != '[';) {
    std::string name = word.substr(0, word.find('.'));
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    const std::string ext = extension_of(word);
    // Slicer hands a node over as a file it writes: an image as a volume (a label map for
    // LABELS), a mesh as a model.
    const std::string tag = name == "image" || name == "labels" ? "image"
                            : (ext == ".vtp" || name == "surface" || name == "mesh") ? "geometry" : "file";
    const std::string type = tag == "geometry" ? " type=\"model\" fileExtensions=\".vtp\""
                             : name == "labels" ? " type=\"label\" fileExtensions=\".nrrd\"" : "";
    // Slicer needs unique names: LABELS beside --labels becomes labels_input.
    if (std::find(flags.begin(), flags.end(), name) != flags.end() ||
        std::find(switches.begin(), switches.end(), name) != switches.end())
      name += "_input";
    x << "    <" << tag << type << ">\n"
      << "      <name>" << identifier(name) << "</name>\n      <label>" << escape(word) << "</label>\n"
      << "      <description>" << escape(word) << ", as in --help</description>\n"
      << "      <channel>input</channel>\n      <index>" << index++ << "</index>\n    </" << tag << ">\n";
  }
  for (const auto& flag : flags) {
    if (flag != "out") continue;
    x << "    <directory>\n      <name>out</name>\n      <longflag>out</longflag>\n      <label>Output folder</label>\n"
      << "      <description>" << escape(explained("out", "DIR")) << "</description>\n    </directory>\n";
  }
  x << "  </parameters>\n";

  x << "  <parameters advanced=\"true\">\n    <label>Options</label>\n"
    << "    <description>Left empty, an option takes the stage's default (--help)</description>\n";
  for (const auto& flag : flags) {
    if (flag == "out") continue;
    const std::string shown = placeholder(synopsis, flag);
    const std::string ext = extension_of(shown);
    const bool file = !ext.empty() && std::isupper(static_cast<unsigned char>(shown[0]));
    const std::string tag = file ? "file" : "string";
    x << "    <" << tag << (file ? " fileExtensions=\"" + escape(ext) + "\"" : "") << ">\n"
      << "      <name>" << identifier(flag) << "</name>\n      <longflag>" << flag << "</longflag>\n"
      << "      <label>" << escape(label_of(flag)) << "</label>\n"
      << "      <description>" << escape(explained(flag, shown)) << "</description>\n"
      << (file ? "      <channel>input</channel>\n" : "") << "    </" << tag << ">\n";
  }
  for (const auto& flag : switches)
    x << "    <boolean>\n      <name>" << identifier(flag) << "</name>\n      <longflag>" << flag << "</longflag>\n"
      << "      <label>" << escape(label_of(flag)) << "</label>\n"
      << "      <description>" << escape(explained(flag, "")) << "</description>\n"
      << "      <default>false</default>\n    </boolean>\n";
  // Slicer passes every parameter that has a value, so this hidden one asks for its protocol.
  x << "    <string-enumeration hidden=\"true\">\n      <name>progress</name>\n      <longflag>progress</longflag>\n"
    << "      <label>Progress</label>\n      <description>Progress reported in Slicer's CLI protocol</description>\n"
    << "      <default>slicer</default>\n      <element>slicer</element>\n      <element>text</element>\n"
    << "      <element>none</element>\n    </string-enumeration>\n";
  x << "  </parameters>\n</executable>\n";
  return x.str();
}

}  // namespace valve
