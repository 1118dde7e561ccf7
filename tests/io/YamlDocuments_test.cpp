#include "io/YamlDocuments.hpp"

#include <catch2/catch.hpp>

#include <string>

using fw::io::load_yaml;
using fw::io::load_yaml_documents;

TEST_CASE("YamlDocuments: a ',' that begins a document is refused at its line instead of parsing forever") {
  // yaml-cpp 0.7 alone loops on each of these, allocating until memory runs out.
  for (const auto& [text, line] : {std::pair<std::string, int>{",", 1}, {"- a\n,", 2}, {"a: 1\n---\n,", 3}}) {
    INFO(text);
    try {
      load_yaml_documents(text);
      FAIL("parsed");
    } catch (const YAML::ParserException& e) {
      CHECK(e.mark.line + 1 == line);
      CHECK_THAT(e.msg, Catch::Contains("cannot get past"));
    }
    CHECK_THROWS_AS(load_yaml(text), YAML::ParserException);
  }
}

TEST_CASE("YamlDocuments: nesting past yaml-cpp's depth limit is refused by what it is, not 'bad file'") {
  // yaml-cpp 0.7 refuses it (its recursion would overflow the stack) with the message of a missing file.
  const std::string text = "a: " + std::string(3000, '[') + std::string(3000, ']');
  CHECK_THROWS_WITH(load_yaml_documents(text), Catch::Contains("nests deeper than the parser's limit of"));
  CHECK_THROWS_AS(load_yaml(text), YAML::ParserException);
}

TEST_CASE("YamlDocuments: texts dense in events load as yaml-cpp loads them") {
  // The guard's bound (two events a byte) holds for the densest texts: empty collections, nulls, aliases,
  // document markers, one-letter scalars.
  for (const std::string text :
       {"", "a", "[[[[[]]]]]", "[,,,,,,]", "{a, b, c}", "- \n- \n- \n", "{a: , b: , c: }",
        "a: &x [1]\nb: *x\nc: *x", "---\n---\n---\n", "x\n...\ny\n...\n"}) {
    INFO(text);
    CHECK(load_yaml_documents(text).size() == YAML::LoadAll(text).size());
    CHECK(YAML::Dump(load_yaml(text)) == YAML::Dump(YAML::Load(text)));
  }
}
