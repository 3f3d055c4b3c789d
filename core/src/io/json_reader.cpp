#include "lub/io/json_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "lub/io/data_path.hpp"

namespace lub {

using nlohmann::json;

namespace {

constexpr size_t kBriefChars = 80;

std::string quoted(const std::string& s) {
  return json(s.size() > kBriefChars ? s.substr(0, kBriefChars) : s)
      .dump(-1, ' ', false, json::error_handler_t::replace);
}

// Appends a compact rendering of `v`, stopping once `out` is longer than kBriefChars: a
// huge or deeply nested value costs O(kBriefChars) time and stack, never a full dump.
void render(const json& v, std::string& out) {
  if (out.size() > kBriefChars) return;
  if (v.is_object() || v.is_array()) {
    const bool obj = v.is_object();
    out += obj ? '{' : '[';
    bool first = true;
    for (auto it = v.begin(); it != v.end() && out.size() <= kBriefChars; ++it) {
      if (!first) out += ',';
      first = false;
      if (obj) out += quoted(it.key()) + ':';
      render(*it, out);
    }
    out += obj ? '}' : ']';
  } else if (v.is_string()) {
    out += quoted(v.get_ref<const std::string&>());
  } else {
    out += v.dump();
  }
}

}  // namespace

std::string brief(const json& value) {
  std::string s;
  render(value, s);
  if (s.size() > kBriefChars) s = s.substr(0, kBriefChars - 3) + "...";
  return s;
}

void fail(const std::string& path, const json& value, const std::string& rule) {
  throw InputError(path + " = " + brief(value) + ": " + rule);
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // Optimal string alignment: insertions, deletions, substitutions and swaps of two
  // neighbours ("viscoisty") each cost 1. Three rows of |b| + 1.
  std::vector<std::size_t> before(b.size() + 1), last(b.size() + 1), row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) last[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], before[j - 2] + 1);
    }
    std::swap(before, last);
    std::swap(last, row);
  }
  return last[b.size()];
}

std::optional<std::string> closest_name(const std::string& word, const std::vector<std::string>& names) {
  // Close: at most a third of the longer name's characters differ (at least 2 may), or one
  // name is the other with something added ("cycles" in "max_cycles").
  std::optional<std::string> best;
  std::size_t best_d = 0;
  for (const std::string& n : names) {
    const std::size_t longer = std::max(n.size(), word.size());
    const std::size_t limit = std::max<std::size_t>(2, longer / 3);
    const std::size_t gap = n.size() > word.size() ? n.size() - word.size() : word.size() - n.size();
    const bool contains = std::min(n.size(), word.size()) >= 4 &&
                          (n.find(word) != std::string::npos || word.find(n) != std::string::npos);
    if (n == word || (gap > limit && !contains)) continue;
    const std::size_t d = edit_distance(word, n);
    if ((d <= limit || contains) && (!best || d < best_d)) best = n, best_d = d;
  }
  return best;
}

namespace {
std::string type_name(const json& v) { return v.type_name(); }
}  // namespace

ObjectReader::ObjectReader(const json& object, std::string path)
    : object_(object), path_(std::move(path)) {
  if (!object_.is_object()) fail(path_.empty() ? "(document)" : path_, object_, "must be a JSON object");
}

std::string ObjectReader::child(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool ObjectReader::has(const std::string& key) const {
  asked_.insert(key);
  return object_.contains(key);
}

const json& ObjectReader::raw(const std::string& key) {
  asked_.insert(key);
  auto it = object_.find(key);
  if (it == object_.end()) {
    // A member not asked about so far whose name is close to the key: a misspelling of it,
    // or a key of its own read later (body_j where body_i is missing), which only the rest
    // of the parse knows (parse_scene asks it).
    std::vector<std::string> unasked, near;
    for (auto m = object_.begin(); m != object_.end(); ++m)
      if (!asked_.count(m.key())) unasked.push_back(m.key());
    while (const std::optional<std::string> n = closest_name(key, unasked)) {  // closest first
      near.push_back(*n);
      unasked.erase(std::find(unasked.begin(), unasked.end(), *n));
    }
    throw MissingKeyError(child(key) + " is missing: required", path_, key, near);
  }
  read_.insert(key);
  return *it;
}

const json* ObjectReader::raw_optional(const std::string& key) {
  asked_.insert(key);
  auto it = object_.find(key);
  if (it == object_.end()) return nullptr;
  read_.insert(key);
  return &*it;
}

std::string ObjectReader::string(const std::string& key) {
  const json& v = raw(key);
  if (!v.is_string()) fail(child(key), v, "must be a string, not " + type_name(v));
  return v.get<std::string>();
}

std::string ObjectReader::string_or(const std::string& key, const std::string& fallback) {
  if (!has(key)) return fallback;
  return string(key);
}

std::string ObjectReader::choice(const std::string& key, const std::vector<std::string>& choices,
                                 const std::optional<std::string>& fallback) {
  if (!has(key) && fallback) return *fallback;
  const std::string s = string(key);
  for (const auto& c : choices)
    if (c == s) return s;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(child(key), raw(key), "must be one of " + list);
}

bool ObjectReader::boolean_or(const std::string& key, bool fallback) {
  const json* v = raw_optional(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(child(key), *v, "must be true or false");
  return v->get<bool>();
}

double ObjectReader::number(const std::string& key, const std::function<bool(double)>& rule,
                            const std::string& rule_text) {
  const json& v = raw(key);
  if (!v.is_number()) fail(child(key), v, "must be a number, not " + type_name(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(child(key), v, "must be finite");
  if (rule && !rule(x)) fail(child(key), v, rule_text);
  return x;
}

double ObjectReader::number_or(const std::string& key, double fallback,
                               const std::function<bool(double)>& rule,
                               const std::string& rule_text) {
  if (!has(key)) return fallback;
  return number(key, rule, rule_text);
}

std::optional<double> ObjectReader::number_optional(const std::string& key,
                                                    const std::function<bool(double)>& rule,
                                                    const std::string& rule_text) {
  if (!has(key)) return std::nullopt;
  return number(key, rule, rule_text);
}

long long ObjectReader::integer(const std::string& key, long long min, long long max) {
  const json& v = raw(key);
  // An integer, or a float with an integral value ("5.0", "1e6"); unsigned values beyond
  // long long and floats beyond 2^53 are out of every range we accept.
  bool ok = false;
  long long x = 0;
  if (v.is_number_unsigned()) {
    ok = max >= 0 && v.get<unsigned long long>() <= static_cast<unsigned long long>(max);
    if (ok) x = static_cast<long long>(v.get<unsigned long long>());
  } else if (v.is_number_integer()) {
    ok = true;
    x = v.get<long long>();
  } else if (v.is_number_float()) {
    const double d = v.get<double>();
    ok = std::isfinite(d) && std::floor(d) == d && std::fabs(d) < 9e15;
    if (ok) x = static_cast<long long>(d);
  }
  if (!ok || x < min || x > max) {
    std::ostringstream rule;
    rule << "must be an integer in [" << min << ", " << max << "]";
    fail(child(key), v, rule.str());
  }
  return x;
}

long long ObjectReader::integer_or(const std::string& key, long long fallback, long long min,
                                   long long max) {
  if (!has(key)) return fallback;
  return integer(key, min, max);
}

Eigen::Vector2d ObjectReader::vec2(const std::string& key) {
  const json& v = raw(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    fail(child(key), v, "must be an array of two numbers [x, y]");
  Eigen::Vector2d out(v[0].get<double>(), v[1].get<double>());
  if (!std::isfinite(out.x()) || !std::isfinite(out.y())) fail(child(key), v, "must be finite");
  return out;
}

Eigen::Vector2d ObjectReader::vec2_or(const std::string& key, const Eigen::Vector2d& fallback) {
  if (!has(key)) return fallback;
  return vec2(key);
}

void ObjectReader::finish() const {
  // The keys this object may have are the ones the parser asked about (read or not).
  const std::vector<std::string> known(asked_.begin(), asked_.end());
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (read_.count(it.key())) continue;
    const std::optional<std::string> near = closest_name(it.key(), known);
    const std::string rule = near ? "unknown key; did you mean `" + *near + "`?"
                                  : "unknown key (check the spelling; the keys: " + data_path("docs/reference/") + ")";
    throw UnknownKeyError(child(it.key()) + " = " + brief(it.value()) + ": " + rule, path_, it.key());
  }
}

const json& require_array(const json& value, const std::string& path) {
  if (!value.is_array()) fail(path, value, "must be an array");
  return value;
}

// --- JSON files ----------------------------------------------------------------------

namespace {

// Refuses a key that appears twice in one object (nlohmann-json would silently keep the
// last one: `"mass_kg": 1, "mass_kg": -1` must not pass as a typo would not). Tracks the
// path of the current value while the parser reports its events.
class DuplicateKeyCheck {
 public:
  bool operator()(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        frames_.push_back({event == json::parse_event_t::array_start, 0, {}, {}});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        element_done();
        break;
      case json::parse_event_t::key: {
        Frame& f = frames_.back();  // an object; the event's value is the key
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw InputError(path() + ": duplicate key (a key may appear only once in an object)");
        break;
      }
      case json::parse_event_t::value:
        element_done();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array = false;
    size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  void element_done() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array)
        p += "[" + std::to_string(f.index) + "]";
      else
        p += (p.empty() ? "" : ".") + f.key;
    }
    return p;
  }
  std::vector<Frame> frames_;
};

// Where parsing stopped, from the byte count nlohmann-json reports (the characters read,
// the offending one last): "line L, column C", both from 1.
std::string text_position(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < end; ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(end - line_start + 1);
}

// The library's reason without its prefixes ("[json.exception.parse_error.101] parse error at
// line 1, column 3: ") and without its "last read: '...'" echo of the input, which may be
// hundreds of characters of the file.
std::string parse_reason(const std::string& what) {
  std::string r = what;
  if (const auto id = r.find("] "); r.rfind("[json.exception.", 0) == 0 && id != std::string::npos)
    r = r.substr(id + 2);
  if (const auto colon = r.find(": "); r.rfind("parse error", 0) == 0 && colon != std::string::npos)
    r = r.substr(colon + 2);
  if (const auto echo = r.find("; last read: '"); echo != std::string::npos) {
    const auto expected = r.rfind("'; expected ");
    r = r.substr(0, echo) + (expected == std::string::npos || expected < echo ? "" : r.substr(expected + 1));
  }
  if (r.size() > 2 * kBriefChars) r = r.substr(0, 2 * kBriefChars - 3) + "...";
  return r;
}

}  // namespace

json parse_json(const std::string& text) {
  DuplicateKeyCheck check;
  const json::parser_callback_t cb = [&check](int /*depth*/, json::parse_event_t event, json& parsed) {
    return check(event, parsed);
  };
  try {
    return json::parse(text, cb);
  } catch (const json::parse_error& e) {
    throw InputError(text_position(text, e.byte) + ": not valid JSON: " + parse_reason(e.what()));
  } catch (const json::exception& e) {  // e.g. out_of_range.406: a number overflows a double
    throw InputError("not valid JSON (a number must fit a double): " + parse_reason(e.what()));
  }
}

json parse_json_text(const std::string& text, const std::string& origin) {
  try {
    return parse_json(text);
  } catch (const InputError& e) {
    throw InputError(origin + ": " + e.what());
  }
}

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) throw InputError("no such file");
  if (status.type() == std::filesystem::file_type::directory) throw InputError("a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(std::string("cannot open the file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (!in.good() && !in.eof()) throw InputError("cannot read the file");
  return text.str();
}

json read_json_file(const std::string& path) {
  std::string text;
  try {
    text = read_text_file(path);
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  return parse_json_text(text, path);
}

namespace {

// "0", "12", or "-" (past the end): what addresses an array element by position.
bool is_array_index(const std::string& token) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  return token == "-" || (!token.empty() && std::all_of(token.begin(), token.end(), digit));
}

// The index (as a token) of the element of `array` whose "name" is `name`; `name` itself if
// no element has a name (the pointer then names nothing, as before); an error listing the
// names if some have one but none this. `where`: the array's pointer.
std::string element_named(const json& array, const std::string& name, const json::json_pointer& where) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const json& e = array[i];
    if (!e.is_object() || !e.contains("name") || !e["name"].is_string()) continue;
    if (e["name"].get<std::string>() == name) return std::to_string(i);
    names.push_back(e["name"].get<std::string>());
  }
  if (names.empty()) return name;
  const std::optional<std::string> near = closest_name(name, names);
  std::string list;
  for (std::size_t i = 0; i < names.size() && i < 12; ++i) list += (i ? ", " : "") + names[i];
  if (names.size() > 12) list += ", ... (" + std::to_string(names.size()) + " names)";
  throw InputError((where.empty() ? std::string("the document") : where.to_string()) + " has no element named " +
                   json(name).dump(-1, ' ', false, json::error_handler_t::replace) +
                   (near ? ": did you mean `" + *near + "`?" : "") + " (its names: " + list + "; or an index 0-" +
                   std::to_string(array.size() - 1) + ")");
}

}  // namespace

json::json_pointer resolve_pointer(const json& doc, const std::string& text) {
  json::json_pointer ptr;
  try {
    ptr = json::json_pointer(text);
  } catch (const json::exception& e) {
    throw InputError(text + " is not a JSON Pointer (RFC 6901): " + parse_reason(e.what()));
  }
  std::vector<std::string> tokens;
  for (json::json_pointer p = ptr; !p.empty(); p.pop_back()) tokens.insert(tokens.begin(), p.back());
  json::json_pointer out;
  const json* at = &doc;
  for (std::string& token : tokens) {
    if (at && at->is_array() && !is_array_index(token)) token = element_named(*at, token, out);
    out.push_back(token);
    if (at && at->is_object() && at->contains(token))
      at = &(*at)[token];
    else if (at && at->is_array() && token != "-" && is_array_index(token) && token.size() < 10 &&
             std::stoul(token) < at->size())
      at = &(*at)[std::stoul(token)];
    else
      at = nullptr;  // a new key, or nothing: the caller's rules say
  }
  return out;
}

void apply_override(json& doc, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set " + assignment + ": must be POINTER=VALUE, e.g. /joints/3/viscosity_Pa_s=0.1");
  const std::string ptr_text = assignment.substr(0, eq);
  const std::string value_text = assignment.substr(eq + 1);
  json::json_pointer ptr;
  try {
    ptr = resolve_pointer(doc, ptr_text);  // /joints/rod_slider/... is /joints/3/...
  } catch (const InputError& e) {
    throw InputError("--set " + assignment + ": " + e.what());
  }
  if (ptr.empty()) throw InputError("--set " + assignment + ": the pointer must not be empty");
  json value;
  try {
    value = json::parse(value_text);
  } catch (const json::parse_error&) {
    value = value_text;  // a bare word is a string
  } catch (const json::exception& e) {
    throw InputError("--set " + assignment + ": " + value_text + " is not a usable JSON value: " + e.what());
  }
  try {
    if (!doc.contains(ptr)) {
      const json::json_pointer parent = ptr.parent_pointer();
      if (!doc.contains(parent) || !doc.at(parent).is_object())
        throw InputError("--set " + assignment + ": " + ptr_text +
                         " names no value of the scene, and its parent is not an object");
    }
    doc[ptr] = value;
  } catch (const json::exception& e) {  // e.g. "/joints//x": an empty token on an array
    throw InputError("--set " + assignment + ": " + ptr_text + " names no value of the scene: " + e.what());
  }
}

}  // namespace lub
