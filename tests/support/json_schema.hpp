#pragma once
// A JSON Schema check for the tests: the subset of draft 2020-12 that ferret's own
// schemas use (type, const, enum, required, properties, additionalProperties: false,
// items, minItems, maxItems, minimum, maximum, oneOf, local $ref). A keyword outside
// the subset is itself an error, so a schema cannot silently go unchecked.

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace ferret::test {

class JsonSchema {
 public:
  explicit JsonSchema(nlohmann::json schema) : root_(std::move(schema)) {}

  /// Every way `doc` breaks the schema ("path: what"); empty when it conforms.
  [[nodiscard]] std::vector<std::string> errors(const nlohmann::json& doc) const {
    std::vector<std::string> out;
    check(root_, doc, "$", out);
    return out;
  }

 private:
  static bool has_type(const nlohmann::json& v, const std::string& type) {
    if (type == "null") return v.is_null();
    if (type == "boolean") return v.is_boolean();
    if (type == "integer")
      return v.is_number_integer() ||
             (v.is_number_float() && v.get<double>() == std::floor(v.get<double>()));
    if (type == "number") return v.is_number();
    if (type == "string") return v.is_string();
    if (type == "array") return v.is_array();
    if (type == "object") return v.is_object();
    return false;
  }

  void check(const nlohmann::json& s, const nlohmann::json& v, const std::string& path,
             std::vector<std::string>& out) const {
    static const std::set<std::string> known{"$schema",
                                             "$id",
                                             "title",
                                             "description",
                                             "$defs",
                                             "type",
                                             "const",
                                             "enum",
                                             "required",
                                             "properties",
                                             "additionalProperties",
                                             "items",
                                             "minItems",
                                             "maxItems",
                                             "minimum",
                                             "maximum",
                                             "oneOf",
                                             "$ref"};
    for (const auto& [key, value] : s.items()) {
      (void)value;
      if (!known.count(key))
        out.push_back(path + ": schema keyword '" + key + "' is not supported by the test");
    }
    if (s.contains("$ref")) {
      const std::string ref = s["$ref"];
      const std::string prefix = "#/$defs/";
      if (ref.rfind(prefix, 0) != 0 || !root_["$defs"].contains(ref.substr(prefix.size()))) {
        out.push_back(path + ": unresolved $ref " + ref);
        return;
      }
      check(root_["$defs"][ref.substr(prefix.size())], v, path, out);
    }
    if (s.contains("type")) {
      bool ok = false;
      if (s["type"].is_string())
        ok = has_type(v, s["type"]);
      else
        for (const auto& t : s["type"]) ok = ok || has_type(v, t);
      if (!ok) {
        out.push_back(path + ": expected type " + s["type"].dump() + ", got " + v.dump());
        return;
      }
    }
    if (s.contains("const") && v != s["const"])
      out.push_back(path + ": expected " + s["const"].dump() + ", got " + v.dump());
    if (s.contains("enum") && std::find(s["enum"].begin(), s["enum"].end(), v) == s["enum"].end())
      out.push_back(path + ": expected one of " + s["enum"].dump() + ", got " + v.dump());
    if (v.is_number()) {
      if (s.contains("minimum") && v.get<double>() < s["minimum"].get<double>())
        out.push_back(path + ": below the minimum " + s["minimum"].dump());
      if (s.contains("maximum") && v.get<double>() > s["maximum"].get<double>())
        out.push_back(path + ": above the maximum " + s["maximum"].dump());
    }
    if (v.is_object()) {
      if (s.contains("required"))
        for (const auto& key : s["required"])
          if (!v.contains(key.get<std::string>()))
            out.push_back(path + ": missing required '" + key.get<std::string>() + "'");
      for (const auto& [key, value] : v.items()) {
        if (s.contains("properties") && s["properties"].contains(key))
          check(s["properties"][key], value, path + "." + key, out);
        else if (s.contains("additionalProperties") && s["additionalProperties"] == false)
          out.push_back(path + ": unexpected property '" + key + "'");
      }
    }
    if (v.is_array()) {
      if (s.contains("minItems") && v.size() < s["minItems"].get<std::size_t>())
        out.push_back(path + ": too few items");
      if (s.contains("maxItems") && v.size() > s["maxItems"].get<std::size_t>())
        out.push_back(path + ": too many items");
      if (s.contains("items"))
        for (std::size_t i = 0; i < v.size(); ++i)
          check(s["items"], v[i], path + "[" + std::to_string(i) + "]", out);
    }
    if (s.contains("oneOf")) {
      int matches = 0;
      for (const auto& option : s["oneOf"]) {
        std::vector<std::string> sub;
        check(option, v, path, sub);
        matches += sub.empty() ? 1 : 0;
      }
      if (matches != 1)
        out.push_back(path + ": matches " + std::to_string(matches) +
                      " of oneOf, expected exactly 1");
    }
  }

  nlohmann::json root_;
};

}  // namespace ferret::test
