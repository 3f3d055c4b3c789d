// Strict reading of JSON input (scenes, grids): every value is checked where it is read,
// and every error names the path, the value and the rule, e.g.
//   joints[2].viscosity_Pa_s = -0.4: must be > 0 Pa s
// Unknown keys are errors (a typo must not silently fall back to a default).
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lub/common/name_table.hpp"

namespace lub {

/// Bad user input: the message names the field, the value and the rule. Programs map it
/// to exit status 2 and create no output file.
class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A required key that an object lacks: "<path> is missing: required". `near`: the members
/// of the object not asked about whose names are close to `key` (misspellings of it?),
/// closest first.
class MissingKeyError : public InputError {
 public:
  MissingKeyError(const std::string& message, std::string object_path, std::string key, std::vector<std::string> near)
      : InputError(message), object_path(std::move(object_path)), key(std::move(key)), near(std::move(near)) {}
  std::string object_path, key;
  std::vector<std::string> near;
};

/// A member no reader asked for: "<path> = <value>: unknown key; did you mean `<key>`?".
class UnknownKeyError : public InputError {
 public:
  UnknownKeyError(const std::string& message, std::string object_path, std::string key)
      : InputError(message), object_path(std::move(object_path)), key(std::move(key)) {}
  std::string object_path, key;
};

/// Edits (insert, delete, substitute, swap two neighbours) from `a` to `b`.
std::size_t edit_distance(const std::string& a, const std::string& b);
/// The name of `names` closest to `word` by edit_distance, if close enough to be what was
/// meant (for "did you mean ...?"); never `word` itself.
std::optional<std::string> closest_name(const std::string& word, const std::vector<std::string>& names);

/// Short rendering of a JSON value for messages (long values are cut).
std::string brief(const nlohmann::json& value);

/// Throws InputError("<path> = <value>: <rule>").
[[noreturn]] void fail(const std::string& path, const nlohmann::json& value,
                       const std::string& rule);

/// Reads the members of one JSON object, checking types and rules, and at `finish()`
/// refuses any member that was not read, naming the closest of the keys it was asked about
/// (its known keys: the parser's reads are the one list of them).
class ObjectReader {
 public:
  ObjectReader(const nlohmann::json& object, std::string path);

  const std::string& path() const { return path_; }
  std::string child(const std::string& key) const;
  bool has(const std::string& key) const;
  /// The raw member (marks it read); throws MissingKeyError if missing.
  const nlohmann::json& raw(const std::string& key);
  /// The raw member if present (marks it read).
  const nlohmann::json* raw_optional(const std::string& key);

  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  /// A string that must be one of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices,
                     const std::optional<std::string>& fallback = std::nullopt);
  /// A string that must name an enumerator of E (its NameTable); `fallback` if absent.
  template <class E>
  E choice_of(const std::string& key, std::optional<E> fallback = std::nullopt) {
    std::optional<std::string> fb;
    if (fallback) fb = std::string(name_of(*fallback));
    return *parse_name<E>(choice(key, names_of<E>(), fb));
  }
  bool boolean_or(const std::string& key, bool fallback);

  /// A finite number; `rule` checks it (nullptr: any finite number) and `rule_text` says
  /// the rule with its unit ("must be > 0 m").
  double number(const std::string& key, const std::function<bool(double)>& rule = nullptr,
                const std::string& rule_text = "");
  double number_or(const std::string& key, double fallback,
                   const std::function<bool(double)>& rule = nullptr,
                   const std::string& rule_text = "");
  std::optional<double> number_optional(const std::string& key,
                                        const std::function<bool(double)>& rule = nullptr,
                                        const std::string& rule_text = "");
  long long integer(const std::string& key, long long min, long long max);
  long long integer_or(const std::string& key, long long fallback, long long min, long long max);
  /// [x, y], finite.
  Eigen::Vector2d vec2(const std::string& key);
  Eigen::Vector2d vec2_or(const std::string& key, const Eigen::Vector2d& fallback);

  /// Errors on any member not read (UnknownKeyError).
  void finish() const;

 private:
  const nlohmann::json& object_;
  std::string path_;
  std::set<std::string> read_;
  mutable std::set<std::string> asked_;  ///< every key asked about, present or not
};

/// Checks `value` is an array and returns it; error names `path`.
const nlohmann::json& require_array(const nlohmann::json& value, const std::string& path);

// Common rules.
inline bool positive(double v) { return v > 0.0; }
inline bool non_negative(double v) { return v >= 0.0; }

/// The text of a file. InputError "no such file", "a directory, not a file" or "cannot open
/// the file: <reason>": the message does not name the file (the caller does, once).
std::string read_text_file(const std::string& path);
/// JSON text; errors (syntax, a key twice in one object, a number too large for a double)
/// throw InputError with no file name: "line 3, column 7: not valid JSON: <short reason>",
/// "bodies[1].mass_kg: duplicate key (...)". The message never echoes the text.
nlohmann::json parse_json(const std::string& text);
/// parse_json, `origin` (a file name) prefixing the messages.
nlohmann::json parse_json_text(const std::string& text, const std::string& origin);
/// read_text_file then parse_json; every message starts with the path ("PATH: no such file").
nlohmann::json read_json_file(const std::string& path);

/// `text` as a JSON Pointer (RFC 6901) into `doc`, where an element of an array of objects
/// may be named by its "name" instead of its index: /joints/rod_slider/viscosity_Pa_s is
/// /joints/3/viscosity_Pa_s where joints[3].name is "rod_slider" (a number is an index).
/// The result has indices only. InputError if `text` is not a pointer, or names an element
/// that no element of a named array has (the message lists the names).
nlohmann::json::json_pointer resolve_pointer(const nlohmann::json& doc, const std::string& text);

/// Applies `--set POINTER=VALUE`: VALUE parsed as JSON, or taken as a string if it is not
/// JSON. The pointer (resolve_pointer: elements by name too) must name an existing value or
/// a new key of an existing object.
void apply_override(nlohmann::json& doc, const std::string& assignment);

}  // namespace lub
