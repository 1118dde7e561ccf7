// Every YAML document of a text, parsed by yaml-cpp, with a guard against yaml-cpp's endless loops.
//
//   const std::vector<YAML::Node> documents = io::load_yaml_documents(text);  // throws YAML::Exception
//
// Why the guard: yaml-cpp 0.7 (Debian 12) never finishes on a document that begins with a ',' outside any
// [ ] or { } (the text "," alone, or "- a\n,"): it hands out empty documents without moving on, each a new
// node, until memory runs out (found by tests/fuzz/scenario_fuzz). So the text is first parsed once only to
// count its events; a YAML text cannot hold more events than kEventsPerByte per byte (a "[]" is two, a
// "---\n" document start and end two), and a parse that goes past that is stopped with a
// YAML::ParserException at the place it is stuck. Only then is the text loaded.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace fw::io {

/// The documents of `text` (YAML::LoadAll), or a YAML::Exception with the mark of the fault, the guard's
/// included.
std::vector<YAML::Node> load_yaml_documents(const std::string& text);

/// The first document of `text` (YAML::Load), guarded the same way; a null node for an empty text.
YAML::Node load_yaml(const std::string& text);

}  // namespace fw::io
