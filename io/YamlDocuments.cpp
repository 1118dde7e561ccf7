#include "io/YamlDocuments.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <sstream>

namespace fw::io {

namespace {

// At most this many parser events per byte of text, and this many for an empty one (see the header).
constexpr std::size_t kEventsPerByte = 2, kEventsOfEmptyText = 8;

// Counts the parser's events and stops it, at the mark of the event past the bound, once there are more than
// any text of this size can hold.
class BoundedEvents : public YAML::EventHandler {
 public:
  explicit BoundedEvents(std::size_t bytes) : limit_(kEventsPerByte * bytes + kEventsOfEmptyText) {}

  void OnDocumentStart(const YAML::Mark& mark) override { count(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { count(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { count(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    count(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    count(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    count(mark);
  }
  void OnMapEnd() override {}

 private:
  void count(const YAML::Mark& mark) {
    if (++events_ > limit_)
      throw YAML::ParserException(mark,
                                  "the YAML parser cannot get past this place (a ',' outside [ ] or { }?)");
  }
  std::size_t limit_, events_ = 0;
};

void check_parser_finishes(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  BoundedEvents events(text.size());
  try {
    while (parser.HandleNextDocument(events)) {
    }
  } catch (const YAML::DeepRecursion& error) {
    // yaml-cpp 0.7 stops nesting past its depth limit, rightly, but says only "bad file".
    throw YAML::ParserException(
        error.mark, fmt::format("the YAML nests deeper than the parser's limit of {} levels", error.depth()));
  }
}

}  // namespace

std::vector<YAML::Node> load_yaml_documents(const std::string& text) {
  check_parser_finishes(text);
  return YAML::LoadAll(text);
}

YAML::Node load_yaml(const std::string& text) {
  check_parser_finishes(text);
  return YAML::Load(text);
}

}  // namespace fw::io
