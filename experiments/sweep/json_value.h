// A small JSON value for the sweep's own files: result.json written by `arbor run`, and the rows of
// results.jsonl. Scalars keep their exact source text so a row re-written by resume or merge is byte-identical.
#ifndef ARBOR_EXPERIMENTS_SWEEP_JSON_VALUE_H_
#define ARBOR_EXPERIMENTS_SWEEP_JSON_VALUE_H_

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace arbor {

struct JsonValue {
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };
  Kind kind = Kind::kNull;
  std::string text;                                       // number/bool: source text; string: decoded
  std::vector<JsonValue> items;                           // arrays
  std::vector<std::pair<std::string, JsonValue>> members;  // objects, in file order

  static JsonValue null() { return {}; }
  static JsonValue string(std::string s) { return {Kind::kString, std::move(s), {}, {}}; }
  // A number from its JSON text (the caller guarantees it is a valid, finite JSON number).
  static JsonValue number(std::string text) { return {Kind::kNumber, std::move(text), {}, {}}; }

  bool is_scalar() const { return kind != Kind::kArray && kind != Kind::kObject; }
  const JsonValue* find(std::string_view name) const;  // object member or nullptr
  // The JSON encoding (compact, members in order).
  std::string encode() const;
  // The value as a CSV cell: strings unquoted, null empty, numbers and bools as written.
  std::string cell() const { return kind == Kind::kNull ? std::string() : text; }
};

// Parses one JSON document; throws InputError(file, line, "", why) on malformed text.
JsonValue parse_json(std::string_view text, const std::string& file, int first_line = 1);

// `"..."` with JSON escapes.
std::string json_quote(std::string_view s);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_JSON_VALUE_H_
