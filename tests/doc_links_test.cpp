// Every image the documentation links exists: README.md and docs/*.md are scanned for Markdown
// images `![alt](path)` and HTML `<img src="path">`; each local path (relative to the file that
// links it) must name an existing file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// The repository root: tests/data's grandparent.
fs::path repo_root() {
    return fs::path(RTLAB_TEST_DATA_DIR).parent_path().parent_path();
}

std::string read_all(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// Image targets linked from Markdown text (without URLs and in-page anchors).
std::vector<std::string> image_links(const std::string& text) {
    static const std::regex md(R"(!\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\))");
    static const std::regex html(R"re(<img[^>]*\ssrc\s*=\s*"([^"]+)")re");
    std::vector<std::string> out;
    for (const std::regex* re : {&md, &html}) {
        for (auto it = std::sregex_iterator(text.begin(), text.end(), *re);
             it != std::sregex_iterator(); ++it) {
            const std::string target = (*it)[1].str();
            if (target.find("://") == std::string::npos && target.rfind('#', 0) != 0) {
                out.push_back(target.substr(0, target.find('#')));
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("image links: the scanner finds Markdown and HTML images", "[docs]") {
    const auto links = image_links(
        "text ![a](plots/x.png) and ![c](http://e.org/p.png)\n"
        "<img width=\"3\" src=\"images/w.png\"> [not an image](other.md)");
    CHECK(links == std::vector<std::string>{"plots/x.png", "images/w.png"});
}

TEST_CASE("every image a doc links exists", "[docs]") {
    const fs::path root = repo_root();
    std::vector<fs::path> docs{root / "README.md"};
    for (const auto& e : fs::directory_iterator(root / "docs")) {
        if (e.path().extension() == ".md") {
            docs.push_back(e.path());
        }
    }
    std::size_t checked = 0;
    for (const fs::path& doc : docs) {
        REQUIRE(fs::exists(doc));
        for (const std::string& link : image_links(read_all(doc))) {
            CAPTURE(doc.string(), link);
            CHECK(fs::is_regular_file(doc.parent_path() / link));
            ++checked;
        }
    }
    CHECK(checked >= 10);  // README's images and docs/results.md's plots at least
}
