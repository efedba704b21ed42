#include "validate/cross_method_report.h"

#include <gtest/gtest.h>

#include <string>

namespace candela {
namespace {

TEST(CrossMethodReport, EscapesHtml) {
  EXPECT_EQ(html_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
  EXPECT_EQ(html_escape("plain"), "plain");
}

TEST(CrossMethodReport, KeyFactsPerMethod) {
  const nlohmann::json path = {{"path", {{"spp", 16}, {"max_depth", 0}}}, {"rays", {{"total", 100}}}};
  const auto path_facts = key_facts("path", path);
  ASSERT_GE(path_facts.size(), 2u);
  EXPECT_EQ(path_facts[0], std::make_pair(std::string("spp"), std::string("16")));
  const nlohmann::json radiosity = {
      {"radiosity", {{"patches", 40}, {"elements", 160}, {"solver", "progressive"}}},
      {"rays", {{"total", 0}}}};
  const auto radiosity_facts = key_facts("radiosity", radiosity);
  ASSERT_EQ(radiosity_facts.size(), 3u);  // no rays: none traced
  EXPECT_EQ(radiosity_facts[0].first, "patches");
  EXPECT_EQ(radiosity_facts[1].second, "160");
  const auto meshless_facts = key_facts("meshless", {{"meshless", {{"sites", 321}}}});
  ASSERT_EQ(meshless_facts.size(), 1u);
  EXPECT_EQ(meshless_facts[0].second, "321");
  EXPECT_TRUE(key_facts("whitted", nlohmann::json::object()).empty());
}

TEST(CrossMethodReport, MethodSettingsFromTheSceneText) {
  const std::string text = "// a comment\n{\"format\": \"candela/1\", \"path\": {\"spp\": 4}}";
  const nlohmann::json settings = method_settings(text, {"path", "radiosity"});
  EXPECT_EQ(settings["path"]["spp"], 4);
  EXPECT_TRUE(settings["radiosity"].is_null());
  EXPECT_TRUE(method_settings("not json", {"path"})["path"].is_null());
}

TEST(CrossMethodReport, PageAndJsonHoldEveryEntry) {
  CrossMethodReport report;
  report.scene_name = "box <1>";
  report.scene_path = "box <1>.json";
  report.width = 2;
  report.height = 1;
  report.reference_spp = 16;
  report.reference.label = report.reference.key = "reference";
  report.reference.seconds = 0.5;
  CrossMethodEntry entry;
  entry.label = entry.method = entry.key = "whitted";
  entry.seconds = 0.25;
  entry.errors.rmse = 0.125;
  entry.errors.psnr = 12.5;
  report.entries.push_back(entry);
  report.difference_scale = 2;
  report.settings = {{"whitted", nullptr}, {"path", {{"spp", 4}}}};
  report.overrides = {"camera.width=2"};

  const std::string html = cross_method_html(report);
  EXPECT_NE(html.find("<title>Cross-method report: box &lt;1&gt;</title>"), std::string::npos);
  EXPECT_EQ(html.find("box <1>"), std::string::npos);  // escaped everywhere
  EXPECT_NE(html.find("src=\"reference.png\""), std::string::npos);
  EXPECT_NE(html.find("src=\"whitted.png\""), std::string::npos);
  EXPECT_NE(html.find("src=\"whitted-diff.png\""), std::string::npos);
  EXPECT_NE(html.find("data-images-loaded=\"pending\""), std::string::npos);
  EXPECT_NE(html.find("<p>defaults</p>"), std::string::npos);
  EXPECT_NE(html.find("--set camera.width=2"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos);  // nothing external

  const nlohmann::json json = cross_method_json(report);
  ASSERT_EQ(json["methods"].size(), 1u);
  EXPECT_EQ(json["methods"][0]["errors"]["rmse"], 0.125);
  EXPECT_EQ(json["methods"][0]["images"]["diff"], "whitted-diff.png");
  EXPECT_EQ(json["reference"]["spp"], 16);
  EXPECT_EQ(json["difference"]["high"], 2.0);
}

}  // namespace
}  // namespace candela
