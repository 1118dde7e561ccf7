// A small streaming JSON writer for the command line's `--json` output (one object on stdout).
//
//   JsonWriter json;
//   json.begin_object();
//   json.key("grid").begin_array().value(128).value(128).value(64).end_array();
//   json.key("cells").values(std::array<int, 3>{128, 128, 64});     // the same, from a range
//   json.key("stages_ms").object(std::map<std::string, double>{{"advect", 1.5}});
//   json.key("ms_per_step").value(42.5);
//   json.end_object();
//   std::cout << json.str() << "\n";
//
// Non-finite numbers are written as null (JSON has no NaN or infinity).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fw::io {

class JsonWriter {
 public:
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(const std::string& name);
  JsonWriter& value(const std::string& text);
  JsonWriter& value(const char* text) { return value(std::string(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(int number) { return value(static_cast<std::int64_t>(number)); }
  JsonWriter& value(std::int64_t number);
  JsonWriter& value(std::uint64_t number);
  JsonWriter& value(unsigned number) { return value(static_cast<std::uint64_t>(number)); }
  JsonWriter& value(bool flag);
  JsonWriter& null();
  /// An array of a range's elements, each as value() writes it.
  template <typename Range>
  JsonWriter& values(const Range& range) {
    begin_array();
    for (const auto& element : range) value(element);
    return end_array();
  }
  /// An object of a map's entries: each key a string, each value as value() writes it.
  template <typename Map>
  JsonWriter& object(const Map& entries) {
    begin_object();
    for (const auto& [name, element] : entries) key(name).value(element);
    return end_object();
  }
  const std::string& str() const { return out_; }

  static std::string escape(const std::string& text);

 private:
  void before_value();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

}  // namespace fw::io
