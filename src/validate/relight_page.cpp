#include "validate/relight_page.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "validate/cross_method_report.h"

namespace candela {

namespace {

const char* kStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1em 0; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }
th { background: #eee; }
td.name, table.facts td { text-align: left; }
#frame { image-rendering: pixelated; width: 512px; max-width: 100%; height: auto; border: 1px solid #888; }
img.thumb { width: 96px; height: auto; border: 2px solid #ccc; cursor: pointer; }
img.thumb.current { border-color: #d33; }
#slider { width: 512px; max-width: 100%; }
)";

// The slider and the thumbnails show a frame; the page's address may name one (page.html#2).
const char* kFrameScript = R"(
function showFrame(index) {
  index = Math.max(0, Math.min(frames.length - 1, index | 0));
  var frame = frames[index];
  document.getElementById('frame').src = frame.image;
  document.getElementById('slider').value = index;
  document.getElementById('caption').textContent = 'Frame ' + (index + 1) + ' of ' + frames.length + ': ' +
      frame.name + ' (' + frame.lights + ') - lighting ' + (1000 * frame.lighting).toFixed(1) + ' ms, ' +
      frame.iterations + ' iterations';
  document.body.setAttribute('data-frame', frame.name);
  var thumbs = document.getElementsByClassName('thumb');
  for (var i = 0; i < thumbs.length; ++i) thumbs[i].className = i === index ? 'thumb current' : 'thumb';
}
window.addEventListener('DOMContentLoaded', function () {
  document.getElementById('slider').addEventListener('input', function (e) { showFrame(+e.target.value); });
  var thumbs = document.getElementsByClassName('thumb');
  for (var i = 0; i < thumbs.length; ++i)
    thumbs[i].addEventListener('click', (function (k) { return function () { showFrame(k); }; })(i));
  showFrame(location.hash ? parseInt(location.hash.substring(1), 10) || 0 : 0);
});
)";

}  // namespace

std::string relight_page_html(const RelightPage& page) {
  nlohmann::json frames = nlohmann::json::array();
  for (const RelightPageFrame& frame : page.frames)
    frames.push_back({{"name", frame.name},
                      {"image", frame.image},
                      {"lights", frame.lights},
                      {"lighting", frame.lighting_seconds},
                      {"iterations", frame.iterations}});
  // The frames as a script literal: JSON, with "</" kept from closing the script element.
  std::string literal = frames.dump();
  for (std::size_t at = literal.find("</"); at != std::string::npos; at = literal.find("</", at + 3))
    literal.replace(at, 2, "<\\/");
  const std::string title = html_escape(page.title);
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<title>" + title + "</title>\n<style>" + std::string(kStyle) + "</style>\n";
  html += "<script>var frames = " + literal + ";\n" + kFrameScript + page_load_check_script() + "</script>\n";
  html += "</head>\n<body data-images-loaded=\"pending\">\n<h1>" + title + "</h1>\n";
  html +=
      "<p>Every frame below comes from one precomputation: the sites, their effective areas and the "
      "transfer S do not depend on the lights or the albedos. A frame is the direct light at the sites "
      "by shadow rays, the series &lambda; = &eta; + QS&lambda; through the stored S, and the "
      "display.</p>\n<table class=\"facts\">\n";
  for (const auto& [label, value] : page.facts)
    html += "<tr><th>" + html_escape(label) + "</th><td>" + html_escape(value) + "</td></tr>\n";
  html += "</table>\n";
  if (!page.frames.empty()) {
    html += "<figure><img id=\"frame\" alt=\"the frame shown\" src=\"" +
            html_escape(page.frames.front().image) + "\"><figcaption id=\"caption\"></figcaption></figure>\n";
    html += fmt::format(
        "<p><input type=\"range\" id=\"slider\" min=\"0\" max=\"{}\" step=\"1\" value=\"0\" "
        "aria-label=\"frame\"></p>\n<p>",
        page.frames.size() - 1);
    for (const RelightPageFrame& frame : page.frames)
      html += "<img class=\"thumb\" alt=\"" + html_escape(frame.name) + "\" title=\"" +
              html_escape(frame.name) + "\" src=\"" + html_escape(frame.image) + "\">\n";
    html +=
        "</p>\n<table>\n<tr><th>frame</th><th>lights</th><th>lighting (ms)</th><th>iterations</th>"
        "<th>whole frame (s)</th></tr>\n";
    for (const RelightPageFrame& frame : page.frames)
      html += fmt::format(
          "<tr><td class=\"name\">{}</td><td class=\"name\">{}</td><td>{:.1f}</td><td>{}</td>"
          "<td>{:.3f}</td></tr>\n",
          html_escape(frame.name), html_escape(frame.lights), 1000 * frame.lighting_seconds, frame.iterations,
          frame.frame_seconds);
    html += "</table>\n";
  }
  html += "<p id=\"image-status\"></p>\n</body>\n</html>\n";
  return html;
}

}  // namespace candela
