// report.html: the figure report as one self-contained page (report_html.hpp).
#include "report_html.hpp"

#include <fstream>
#include <iterator>

#include "rootsim/errors.hpp"
#include "rootsim/version.hpp"

namespace fs = std::filesystem;

namespace rootsim::fig {

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

std::string htmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

namespace {
std::string readPanel(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw RunError("report.html: cannot read " + file.string());
  if (bytes.empty()) throw RunError("report.html: panel " + file.string() + " is missing or empty");
  return bytes;
}
}  // namespace

std::string reportHtml(const std::string& command, const std::vector<Claim>& claims,
                       const std::vector<std::string>& panels, const fs::path& dir) {
  int ok = 0;
  for (const auto& cl : claims) ok += cl.agrees;
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>rootsim figure report</title>\n"
      "<style>\n"
      "body{font-family:sans-serif;margin:2em;max-width:1100px;color:#222;background:#fff}\n"
      "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #999;padding:4px 8px;vertical-align:top}\n"
      "th{background:#eee}tr.agree td.verdict{background:#c8f0c8;color:#064d06;font-weight:bold}\n"
      "tr.disagree td.verdict{background:#f6c6c6;color:#8b0000;font-weight:bold}\n"
      "img{max-width:100%;border:1px solid #ccc}code{background:#f4f4f4;padding:1px 3px}\n"
      "</style>\n</head>\n<body>\n<h1>rootsim figure report</h1>\n<p>rootsim " +
      htmlEscape(kVersion) + ". Panels made by <code>" + htmlEscape(command) +
      "</code>; the definitions, tolerances and each panel's text are in report.md beside this file.</p>\n"
      "<h2>Claims</h2>\n<p>" +
      std::to_string(ok) + " of " + std::to_string(claims.size()) +
      " claims agree within their stated tolerance.</p>\n<table id=\"claims\">\n"
      "<tr><th>claim</th><th>theory</th><th>paper</th><th>measured</th><th>tolerance</th><th>agrees</th></tr>\n";
  for (const auto& cl : claims) {
    h += std::string("<tr class=\"") + (cl.agrees ? "agree" : "disagree") + "\"><td>" + htmlEscape(cl.what) +
         "</td><td>" + htmlEscape(cl.theory) + "</td><td>" + htmlEscape(cl.paper) + "</td><td>" +
         htmlEscape(cl.measured) + "</td><td>" + htmlEscape(cl.tolerance) + "</td><td class=\"verdict\">" +
         (cl.agrees ? "agrees" : "disagrees") + "</td></tr>\n";
  }
  h += "</table>\n";
  if (ok < static_cast<int>(claims.size())) {
    h += "<h3>Not reproduced</h3>\n<ul>\n";
    for (const auto& cl : claims)
      if (!cl.agrees)
        h += "<li><b>" + htmlEscape(cl.what) + "</b>: measured " + htmlEscape(cl.measured) + " against " +
             htmlEscape(cl.theory) + " (tolerance " + htmlEscape(cl.tolerance) + "). " + htmlEscape(cl.note) + "</li>\n";
    h += "</ul>\n";
  }
  for (const auto& name : panels)
    h += "<h2 id=\"" + htmlEscape(name) + "\">" + htmlEscape(name) + "</h2>\n<img class=\"panel\" alt=\"" +
         htmlEscape(name) + "\" src=\"data:image/png;base64," + base64(readPanel(dir / (name + ".png"))) + "\">\n";
  // marks every picture loaded or not once the page has loaded, for a headless browser's check
  // (tests/figure/report_html_check.py)
  h += "<script>\nwindow.addEventListener('load', function () {\n"
       "  var bad = 0, imgs = document.images;\n"
       "  for (var i = 0; i < imgs.length; ++i) {\n"
       "    var good = imgs[i].complete && imgs[i].naturalWidth > 0;\n"
       "    imgs[i].setAttribute('data-loaded', good ? 'yes' : 'no');\n"
       "    if (!good) ++bad;\n"
       "  }\n"
       "  document.body.setAttribute('data-images', imgs.length + ' ' + bad);\n"
       "});\n</script>\n</body>\n</html>\n";
  return h;
}

}  // namespace rootsim::fig
