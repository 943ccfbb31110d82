#include "io/check_report.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "core/image.h"
#include "io/image_io.h"

namespace ssrt {

namespace fs = std::filesystem;

namespace {

// Text for HTML and XML: the five characters that could end an element or an attribute.
std::string escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

// Failed, erroring, stale and new cases first (the ones a person opens the page for).
std::vector<const ReportCase*> pageOrder(const CheckReport& report) {
    std::vector<const ReportCase*> order;
    for (const ReportCase& c : report.cases) order.push_back(&c);
    std::stable_sort(order.begin(), order.end(), [](const ReportCase* a, const ReportCase* b) {
        const auto rank = [](const ReportCase* c) {
            return c->status == "PASS" || c->status == "UPDATED" ? 1 : 0;
        };
        return rank(a) < rank(b);
    });
    return order;
}

constexpr const char* kStyle = R"(body{font:14px sans-serif;margin:1em 2em;color:#222}
h2{font-size:16px;margin:1.2em 0 .3em}
.status{display:inline-block;min-width:5em;padding:1px 6px;margin-right:.5em;color:#fff;background:#3a3}
.FAIL .status,.ERROR .status{background:#c33}.STALE .status,.NEW .status{background:#c80}
.UPDATED .status{background:#36c}
pre{background:#f4f4f4;padding:4px 6px;white-space:pre-wrap}
.images{display:flex;flex-wrap:wrap;gap:12px}
figure{margin:0}figcaption{font-size:12px;color:#555}
img{width:320px;image-rendering:pixelated;display:block;background:#888}
.swap{position:relative}.swap img.ref{position:absolute;left:0;top:0;opacity:0}
.swap:hover img.ref{opacity:1}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}
tr.bad td{background:#fdd}
)";

// Records, for a headless browser, how many images loaded and any that did not.
constexpr const char* kScript = R"(<script>
const errors = [];
window.addEventListener('error', e => errors.push(String(e.message || e.type)));
window.addEventListener('load', () => {
  const images = Array.from(document.images);
  const failed = images.filter(i => !i.complete || i.naturalWidth === 0);
  document.body.dataset.images = String(images.length);
  document.body.dataset.imagesFailed = failed.map(i => i.getAttribute('src')).join(' ');
  document.body.dataset.errors = errors.join(' | ');
  document.body.dataset.loaded = 'yes';
});
</script>
)";

void figure(std::ostringstream& h, const std::string& src, const std::string& caption) {
    if (src.empty()) return;
    h << "<figure><img src=\"" << escaped(src) << "\" alt=\"" << escaped(caption)
      << "\"><figcaption>" << escaped(caption) << "</figcaption></figure>\n";
}

void caseSection(std::ostringstream& h, const ReportCase& c) {
    h << "<section class=\"case " << escaped(c.status) << "\" id=\"case-" << escaped(c.name)
      << "\">\n<h2><span class=\"status\">" << escaped(c.status) << "</span>" << escaped(c.name)
      << "</h2>\n<p>" << escaped(c.message) << "</p>\n";
    h << "<p>reference: <code>" << escaped(c.reference) << "</code></p>\n";
    h << "<pre class=\"command\">" << escaped(c.command) << "</pre>\n<div class=\"images\">\n";
    if (!c.newImage.empty() && !c.referenceImage.empty())
        h << "<figure class=\"swap\"><img class=\"new\" src=\"" << escaped(c.newImage)
          << "\" alt=\"new\"><img class=\"ref\" src=\"" << escaped(c.referenceImage)
          << "\" alt=\"reference\"><figcaption>new (pointer on it: the reference)</figcaption>"
             "</figure>\n";
    else figure(h, c.newImage, "new");
    figure(h, c.referenceImage, "reference");
    figure(h, c.diffImage,
           "difference of the colour (black: equal; dark red to white: up to its largest)");
    figure(h, c.flipImage, "FLIP (magma: black 0 to pale yellow 1)");
    h << "</div>\n";
    if (!c.flipLine.empty()) h << "<p>" << escaped(c.flipLine) << "</p>\n";
    if (c.layers.empty()) {
        h << "</section>\n";
        return;
    }
    h << "<table><tr><th>layer</th><th>channels</th><th>max difference</th><th>at</th>"
         "<th>pixels over</th><th>hash (new)</th><th>rule</th><th>verdict</th></tr>\n";
    for (const ReportLayer& l : c.layers) {
        h << "<tr" << (l.bad ? " class=\"bad\"" : "") << ">";
        for (const std::string* cell : {&l.name, &l.channels, &l.maxError, &l.where, &l.pixelsOver,
                                        &l.hash, &l.rule, &l.verdict})
            h << "<td>" << escaped(*cell) << "</td>";
        h << "</tr>\n";
    }
    h << "</table>\n</section>\n";
}

}  // namespace

void writeHtmlReport(const std::string& path, const CheckReport& report) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>ssrt "
         "check: "
      << escaped(report.suite) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
    h << "<h1>ssrt check: " << escaped(report.suite) << "</h1>\n<p class=\"summary\">"
      << escaped(report.summary) << "</p>\n";
    for (const ReportCase* c : pageOrder(report)) caseSection(h, *c);
    h << kScript << "</body>\n</html>\n";
    writeTextWhole(path, h.str());
}

void writeJunitReport(const std::string& path, const CheckReport& report) {
    int failures = 0, errors = 0;
    double seconds = 0.0;
    for (const ReportCase& c : report.cases) {
        failures += c.outcome == ReportOutcome::Failure ? 1 : 0;
        errors += c.outcome == ReportOutcome::Error ? 1 : 0;
        seconds += c.seconds;
    }
    std::ostringstream x;
    x << std::fixed << std::setprecision(3);
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\""
      << escaped(report.suite) << "\" tests=\"" << report.cases.size() << "\" failures=\""
      << failures << "\" errors=\"" << errors << "\" skipped=\"0\" time=\"" << seconds << "\">\n";
    for (const ReportCase& c : report.cases) {
        x << "<testcase classname=\"ssrt.check\" name=\"" << escaped(c.name) << "\" time=\""
          << c.seconds << "\"";
        if (c.outcome == ReportOutcome::Pass) {
            x << "/>\n";
            continue;
        }
        const char* tag = c.outcome == ReportOutcome::Error ? "error" : "failure";
        x << ">\n<" << tag << " type=\"" << escaped(c.status) << "\" message=\""
          << escaped(c.message) << "\">" << escaped(c.command) << "</" << tag << ">\n</testcase>\n";
    }
    x << "</testsuite>\n</testsuites>\n";
    writeTextWhole(path, x.str());
}

void writePreviewPng(const std::string& image, const std::string& png) {
    const std::vector<std::string> names = readChannelNames(image);
    const auto has = [&](const std::string& n) {
        return std::find(names.begin(), names.end(), n) != names.end();
    };
    std::vector<std::string> rgb;
    for (const std::string prefix : {"display.", "", "color."})
        if (has(prefix + "R") && has(prefix + "G") && has(prefix + "B")) {
            rgb = {prefix + "R", prefix + "G", prefix + "B"};
            break;
        }
    if (rgb.empty()) {
        if (names.empty()) throw std::runtime_error("'" + image + "' has no channel to show");
        rgb = {names.front(), names.front(), names.front()};
    }
    int w = 0, h = 0;
    const std::vector<std::vector<float>> values = readChannels(image, rgb, w, h);
    PlaneF planes[3] = {PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)};
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) planes[c].at(x, y) = values[c][std::size_t(y) * w + x];
    writeDisplayPng(png, planes[0], planes[1], planes[2]);
}

}  // namespace ssrt
