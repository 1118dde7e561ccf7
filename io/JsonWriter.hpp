// A small streaming JSON writer for the command line's `--json` output (one object on stdout).
//
//   JsonWriter json;
//   json.begin_object();
//   json.key("grid").begin_array().value(128).value(128).value(64).end_array();
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
  const std::string& str() const { return out_; }

  static std::string escape(const std::string& text);

 private:
  void before_value();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

}  // namespace fw::io
