// The reproduction gallery (docs/FIGURES.md, written by scripts/figures.sh)
// shows every figure scene of the suite, and every picture it links exists:
// a figure scene added without regenerating the gallery fails here.
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "test_support.h"

namespace {

const std::string kGallerySource = aniso::test::kSourceDir;

// The figure numbers in the TEST_CASE names ("fig. 5: ...") of one test file.
std::set<std::string> gallery_figures_tested(const std::string& file) {
  const std::string text = aniso::test::slurp(kGallerySource + "/tests/" + file);
  REQUIRE_FALSE(text.empty());
  const std::regex name(R"(TEST_CASE\("[^"]*\bfig\. (\d+))");
  std::set<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), name); it != std::sregex_iterator(); ++it) {
    out.insert((*it)[1]);
  }
  return out;
}

}  // namespace

TEST_CASE("docs/FIGURES.md has a section for every figure scene and every picture it links exists", "[docs]") {
  const std::string gallery = aniso::test::slurp(kGallerySource + "/docs/FIGURES.md");
  REQUIRE_FALSE(gallery.empty());
  std::set<std::string> tested;
  for (const char* file : {"test_paper_figures.cpp", "test_figures_post.cpp", "test_flatten.cpp"}) {
    for (const std::string& figure : gallery_figures_tested(file)) tested.insert(figure);
  }
  CHECK(tested.size() >= 10);
  for (const std::string& figure : tested) {
    INFO("fig. " << figure);
    CHECK(gallery.find("\n## Fig. " + figure + ":") != std::string::npos);
  }
  const std::regex picture(R"(\]\((figures/[^)]+\.png)\))");
  int pictures = 0;
  for (auto it = std::sregex_iterator(gallery.begin(), gallery.end(), picture); it != std::sregex_iterator(); ++it) {
    INFO((*it)[1]);
    CHECK(std::filesystem::is_regular_file(kGallerySource + "/docs/" + std::string((*it)[1])));
    ++pictures;
  }
  CHECK(pictures >= 2 * static_cast<int>(tested.size()));
}
