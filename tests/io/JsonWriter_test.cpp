#include "io/JsonWriter.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

using fw::io::JsonWriter;

TEST_CASE("JsonWriter: nested objects and arrays get commas between elements only") {
  JsonWriter json;
  json.begin_object();
  json.key("grid").begin_array().value(128).value(64).value(32).end_array();
  json.key("stages_ms").begin_object();
  json.key("advect").value(1.5);
  json.key("project").value(2.25);
  json.end_object();
  json.key("cases").begin_array();
  json.begin_object().key("nodes").value(10).key("ok").value(true).end_object();
  json.begin_object().key("nodes").value(20).key("ok").value(false).end_object();
  json.begin_array().end_array();
  json.end_array();
  json.key("empty").begin_object().end_object();
  json.key("nothing").null();
  json.end_object();
  CHECK(json.str() ==
        R"({"grid":[128,64,32],"stages_ms":{"advect":1.5,"project":2.25},)"
        R"("cases":[{"nodes":10,"ok":true},{"nodes":20,"ok":false},[]],"empty":{},"nothing":null})");
}

TEST_CASE("JsonWriter: a range is an array and a map an object, each element as value() writes it") {
  JsonWriter json;
  json.begin_object();
  json.key("grid").values(std::array<int, 3>{128, 64, 32});
  json.key("hz").values(std::vector<double>{0.5, 1.25});
  json.key("none").values(std::vector<int>{});
  json.key("stages_ms").object(std::map<std::string, double>{{"project", 2.25}, {"advect", 1.5}});
  json.end_object();
  CHECK(json.str() ==
        R"({"grid":[128,64,32],"hz":[0.5,1.25],"none":[],"stages_ms":{"advect":1.5,"project":2.25}})");
}

TEST_CASE("JsonWriter: strings escape quotes, backslashes, newlines and control characters") {
  CHECK(JsonWriter::escape("plain") == "\"plain\"");
  CHECK(JsonWriter::escape("") == "\"\"");
  CHECK(JsonWriter::escape("say \"hi\"") == R"("say \"hi\"")");
  CHECK(JsonWriter::escape("C:\\pocl\\") == R"("C:\\pocl\\")");
  CHECK(JsonWriter::escape("line 1\nline 2") == R"("line 1\nline 2")");
  CHECK(JsonWriter::escape("a\tb\rc") == R"("a\tb\rc")");
  CHECK(JsonWriter::escape(std::string("\x01\x1f", 2)) == R"("\u0001\u001f")");
  CHECK(JsonWriter::escape(std::string("nul\0byte", 8)) == R"("nul\u0000byte")");
  // Printable ASCII and UTF-8 pass through unchanged.
  CHECK(JsonWriter::escape("x/y ~ \xc3\xa9") == "\"x/y ~ \xc3\xa9\"");

  JsonWriter json;
  json.begin_object().key("a \"key\"").value("v\\al\nue").end_object();
  CHECK(json.str() == R"({"a \"key\"":"v\\al\nue"})");
}

TEST_CASE("JsonWriter: non-finite numbers are written as null") {
  JsonWriter json;
  json.begin_array()
      .value(std::numeric_limits<double>::quiet_NaN())
      .value(1.5)
      .value(std::numeric_limits<double>::infinity())
      .value(-std::numeric_limits<double>::infinity())
      .end_array();
  CHECK(json.str() == "[null,1.5,null,null]");

  JsonWriter keyed;
  keyed.begin_object().key("max_divergence").value(std::nan("")).end_object();
  CHECK(keyed.str() == R"({"max_divergence":null})");
}

TEST_CASE("JsonWriter: numbers keep their full range and round-trip") {
  JsonWriter json;
  json.begin_array()
      .value(std::numeric_limits<std::int64_t>::min())
      .value(std::numeric_limits<std::uint64_t>::max())
      .value(0.1)
      .value(-2.0)
      .value(1e300)
      .value(7u)
      .end_array();
  CHECK(json.str() == "[-9223372036854775808,18446744073709551615,0.1,-2,1e+300,7]");
  // Shortest round-trip representation of a double.
  JsonWriter third;
  third.value(1.0 / 3.0);
  CHECK(std::stod(third.str()) == 1.0 / 3.0);
}

TEST_CASE("JsonWriter: closing a container that was never opened is a logic error") {
  JsonWriter json;
  CHECK_THROWS_AS(json.end_object(), std::logic_error);
  CHECK_THROWS_AS(json.end_array(), std::logic_error);
}
