#include "scene/yaml_load.h"

#include <fstream>
#include <sstream>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

namespace peensim {

namespace {

// Counts the open maps and lists while the parser streams the text's events: linear in the text,
// aliases not expanded (an alias is one event), so a hostile text cannot make the count slow.
class NestingCheck : public YAML::EventHandler {
public:
    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override { open(mark); }
    void OnSequenceEnd() override { --depth_; }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override { open(mark); }
    void OnMapEnd() override { --depth_; }

private:
    void open(const YAML::Mark& mark) {
        if (++depth_ > kMaxYamlNesting) throw YAML::ParserException(mark, yaml_nesting_problem());
    }
    int depth_ = 0;
};

}  // namespace

std::string yaml_nesting_problem() {
    return "maps and lists nested deeper than " + std::to_string(kMaxYamlNesting) + " levels; expected at most " +
           std::to_string(kMaxYamlNesting) + " (a scene needs fewer than 10)";
}

YAML::Node load_yaml(const std::string& text) {
    {
        std::istringstream in(text);
        YAML::Parser parser(in);
        NestingCheck check;
        try {
            parser.HandleNextDocument(check);  // the first document: the one YAML::Load reads
        } catch (const YAML::DeepRecursion& e) {
            // yaml-cpp's own guard fired first (its message is only "bad file"): the same limit's words.
            throw YAML::ParserException(e.mark, yaml_nesting_problem());
        }
    }
    return YAML::Load(text);
}

YAML::Node load_yaml_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw YAML::BadFile(path);
    std::ostringstream text;
    text << in.rdbuf();
    return load_yaml(text.str());
}

}  // namespace peensim
