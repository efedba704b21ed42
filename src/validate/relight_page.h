// The relighting page — `candela render SCENE --method meshless --relight
// FRAMES.json -o out.png --relight-page page.html` writes one HTML page with every frame (the
// scene's own lights first), a slider over them, each frame's lighting time and iterations, and
// what was precomputed once. Self-contained but for the frames' PNGs, which it names relative to
// its own folder; `page.html#3` opens at the fourth frame. Opened in headless Chromium by the tests,
// like the report's page.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace candela {

struct RelightPageFrame {
  std::string name;
  std::string image;            // relative to the page's folder
  std::string lights;           // what lights the frame, in words
  double lighting_seconds = 0;  // direct light and the iteration
  double frame_seconds = 0;     // the whole render
  int iterations = 0;
};

struct RelightPage {
  std::string title;
  std::vector<std::pair<std::string, std::string>> facts;  // the precomputation, label and value
  std::vector<RelightPageFrame> frames;
};

std::string relight_page_html(const RelightPage& page);

}  // namespace candela
