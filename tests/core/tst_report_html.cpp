// The identify report's HTML page (report_html.hpp): htmlEscape, the hand-written SVG line plot
// (one balanced <svg> element, one path and legend entry per series, data mapped into the plot
// frame, non-finite points breaking the line) and renderHtmlReport on a hand-made IdentifyResult
// (a complete document that shows the numbers it was given and escapes every user string: run
// files come from the command line and may hold any text).
#include <QtTest>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "core/identify/identify.hpp"
#include "core/identify/report_html.hpp"

using namespace stickslip::identify;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

size_t count(const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + what.size())) ++n;
    return n;
}

bool has(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

// The inverse of htmlEscape (for the round trip): the four entities back to their characters.
std::string unescape(const std::string& s) {
    static const std::vector<std::pair<std::string, char>> entities = {{"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}};
    std::string o;
    for (size_t i = 0; i < s.size();) {
        bool hit = false;
        for (const auto& [e, c] : entities)
            if (s.compare(i, e.size(), e) == 0) {
                o += c;
                i += e.size();
                hit = true;
                break;
            }
        if (!hit) o += s[i++];
    }
    return o;
}

// Every element opened is closed, in order; HTML's void elements and <!DOCTYPE> stand alone,
// and no '<' occurs inside a tag (which text that was not escaped would produce). Empty when
// well formed, else what is wrong.
std::string tagProblem(const std::string& s) {
    static const std::set<std::string> voids = {"meta", "br", "hr", "img", "input", "link"};
    std::vector<std::string> open;
    for (size_t p = s.find('<'); p != std::string::npos; p = s.find('<', p + 1)) {
        const size_t e = s.find('>', p);
        if (e == std::string::npos) return "unterminated tag at " + std::to_string(p);
        const std::string tag = s.substr(p + 1, e - p - 1);
        if (tag.find('<') != std::string::npos) return "'<' inside the tag at " + std::to_string(p);
        if (tag.empty() || tag[0] == '!') continue;
        const bool closing = tag[0] == '/', selfClosing = tag.back() == '/';
        const std::string body = closing ? tag.substr(1) : tag;
        const std::string name = body.substr(0, body.find_first_of(" \n/"));
        if (closing) {
            if (open.empty() || open.back() != name)
                return "</" + name + "> closes <" + (open.empty() ? std::string("nothing") : open.back()) + ">";
            open.pop_back();
        } else if (!selfClosing && !voids.count(name)) {
            open.push_back(name);
        }
    }
    return open.empty() ? std::string() : "<" + open.back() + "> is never closed";
}

// The commands of every <path d="…"> in order: 'M' or 'L' with the point's pixel coordinates.
struct PathCmd {
    char op;
    double x, y;
};
std::vector<std::vector<PathCmd>> paths(const std::string& svg) {
    std::vector<std::vector<PathCmd>> out;
    const std::string key = "<path d=\"";
    for (size_t p = svg.find(key); p != std::string::npos; p = svg.find(key, p + 1)) {
        const size_t b = p + key.size(), e = svg.find('"', b);
        const std::string d = svg.substr(b, e - b);
        std::vector<PathCmd> cmds;
        const char* c = d.c_str();
        while (*c == 'M' || *c == 'L') {
            char* end = nullptr;
            PathCmd k{*c, 0, 0};
            k.x = std::strtod(c + 1, &end);
            k.y = std::strtod(end, &end);
            cmds.push_back(k);
            c = end;
        }
        if (*c != '\0') qFatal("unparsed path data: %s", c);
        out.push_back(cmds);
    }
    return out;
}

// The plot frame of a W × H plot (report_html.cpp: margins 70, 15, 28, 42).
struct Frame {
    double left, right, top, bottom;
};
Frame frameOf(int W, int H) { return {70.0, W - 15.0, 28.0, H - 42.0}; }

// A result with one effect added, one candidate rejected (trading off with η), one run and
// its trace; every number distinct, so that each can be found on the page.
IdentifyResult handMadeResult() {
    IdentifyResult r;
    r.ok = true;
    r.setup = "prescribed";
    r.residual = "prescribed";
    r.fits = 137;
    r.wallTime_s = 12.34;
    r.timeline = {{"baseline", 0.02, 4.56, 130}, {"round 1: <lag>", 4.56, 12.3, 7}};
    r.before.fitNrmse = 0.1234;
    r.before.validationNrmse = 0.2345;
    r.after.fitNrmse = 0.05671;
    r.after.validationNrmse = 0.06782;
    r.before.runs = {RunError{"run_01.csv", "fit", 0.5, 0.1111, 0.2222}};
    r.after.runs = {RunError{"run_01.csv", "fit", 0.2, 0.03333, 0.04444}};
    AddedEffect e;
    e.name = "frictional_lag";
    e.params = {{"frictional_lag.tau_s", 0.01234, 0.00056}};
    e.deltaBic = -42.5;
    e.pointedBy = {{"dF/dt", 0.612}};
    r.effectsAdded = {e};
    CandidateScore added;
    added.name = "frictional_lag";
    added.round = 1;
    added.accepted = true;
    added.deltaBic = -42.5;
    CandidateScore rejected;
    rejected.name = "backlash";
    rejected.round = 1;
    rejected.deltaBic = 3.2;
    rejected.reason = "dBIC = 3.2 is not below -10";
    rejected.tradesOffWithBaseline = "eta";
    rejected.sizeCorrelation = {{"eta", 0.987}};
    r.candidates = {added, rejected};
    r.baseline = {{"mu", 0.3125, 0.0021}, {"eta", 1.75, kNaN}};  // η not identifiable: NaN stderr
    r.final = {{"mu", 0.3126, 0.0019}};
    r.diagnosticsBefore.correlations = {{"dF/dt", 0.612}};
    r.diagnosticsAfter.correlations = {{"dF/dt", 0.021}};
    r.diagnosticsBefore.whiteness.acf = {1.0, 0.6, 0.3};
    r.diagnosticsAfter.whiteness.acf = {1.0, 0.1, 0.0};
    r.diagnosticsBefore.spectrum = {{0, 1, 2, 3}, {1, 2, 4, 0.5}, {2.5}, 0.3};
    RunTrace t;
    t.file = "run_01.csv";
    t.t_s = {0, 0.001, 0.002, 0.003};
    t.relVel_mps = {0.0, 0.01, 0.02, 0.01};
    t.measured_N = {1.0, 1.5, 1.8, 1.6};
    t.before_N = {1.1, 1.4, 1.7, 1.7};
    t.after_N = {1.0, 1.5, 1.8, 1.6};
    r.traces = {t};
    return r;
}

}  // namespace

class TstReportHtml : public QObject {
    Q_OBJECT
private slots:
    // The four characters that end HTML text or a quoted attribute become entities; everything
    // else (apostrophes, UTF-8, entities already written) passes byte for byte, so an author's
    // literal "&amp;" stays visible as such ("&amp;amp;") and unescaping gives the input back.
    void htmlEscapeEscapesExactlyTheFourCharacters() {
        QCOMPARE(htmlEscape(""), std::string());
        QCOMPARE(htmlEscape("plain text 0.5 mm/s"), std::string("plain text 0.5 mm/s"));
        QCOMPARE(htmlEscape("a&b<c>d\"e'f"), std::string("a&amp;b&lt;c&gt;d&quot;e'f"));
        QCOMPARE(htmlEscape("&amp;"), std::string("&amp;amp;"));
        QCOMPARE(htmlEscape("<<>>"), std::string("&lt;&lt;&gt;&gt;"));
        QCOMPARE(htmlEscape("μ = 0.3 ± 0.01 – ε_T"), std::string("μ = 0.3 ± 0.01 – ε_T"));
        std::string all;
        for (int c = 1; c < 256; ++c) all += static_cast<char>(c);
        const std::string escaped = htmlEscape(all);
        for (char c : {'<', '>', '"'}) QVERIFY2(escaped.find(c) == std::string::npos, std::string(1, c).c_str());
        QCOMPARE(count(escaped, "&"), size_t(4));  // one per entity, none left bare
        QCOMPARE(escaped.size(), all.size() - 4 + 5 + 4 + 4 + 6);
        QCOMPARE(unescape(escaped), all);
        const std::string tricky = "&lt; is not < and &quot;&\"";
        QCOMPARE(unescape(htmlEscape(tricky)), tricky);
    }

    // One <svg> element of the requested size whose tags balance, with one path and one legend
    // entry (the series' colour and label) per series; title, axis labels and legend names are
    // escaped, so text with '<' cannot open an element.
    void svgIsOneBalancedElementWithAPathPerSeries() {
        const SvgSeries a{{0, 1, 2, 3}, {0, 1, 4, 9}, "#c33", "before"};
        const SvgSeries b{{0, 1, 2, 3}, {1, 1, 1, 1}, "#36c", "after & <more>"};
        const std::string svg = svgLinePlot({a, b}, "F <vs> t", "t [s]", "F \"measured\" [N]", 500, 250);
        QVERIFY(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"500\" height=\"250\" viewBox=\"0 0 500 250\"", 0) == 0);
        QVERIFY(svg.size() >= 7 && svg.compare(svg.size() - 7, 7, "</svg>\n") == 0);
        QCOMPARE(count(svg, "<svg"), size_t(1));
        QCOMPARE(count(svg, "</svg>"), size_t(1));
        const std::string problem = tagProblem(svg);
        QVERIFY2(problem.empty(), problem.c_str());
        QCOMPARE(count(svg, "<path "), size_t(2));
        QVERIFY(has(svg, "stroke=\"#c33\"") && has(svg, "stroke=\"#36c\""));
        QVERIFY(has(svg, ">F &lt;vs&gt; t</text>"));
        QVERIFY(has(svg, ">t [s]</text>"));
        QVERIFY(has(svg, ">F &quot;measured&quot; [N]</text>"));
        QVERIFY(has(svg, ">before</text>"));
        QVERIFY(has(svg, ">after &amp; &lt;more&gt;</text>"));
        QVERIFY(!has(svg, "<vs>") && !has(svg, "<more>"));
        // The checker itself sees unescaped text and crossed tags.
        QVERIFY(!tagProblem("<svg><text>a<b</text></svg>").empty());
        QVERIFY(!tagProblem("<p><b></p></b>").empty());
        QVERIFY(!tagProblem("<svg><path d=\"\"/>").empty());
        // No series: still a balanced, empty frame, with ticks on both axes (the unit frame; the
        // y axis once had none, its range left at ±∞).
        const std::string empty = svgLinePlot({}, "nothing", "x", "y");
        QVERIFY2(tagProblem(empty).empty(), tagProblem(empty).c_str());
        QCOMPARE(count(empty, "<path "), size_t(0));
        QVERIFY(count(empty, "text-anchor=\"end\">") >= 2);
    }

    // Each finite point is one path command, in order: the data's x range spans the frame's width
    // exactly, y grows upwards (SVG's y grows downwards) with 5 % headroom above and below, and
    // the mapping is linear in both.
    void pathPointsMapLinearlyIntoThePlotFrame() {
        const int W = 640, H = 300;
        const Frame f = frameOf(W, H);
        const SvgSeries s{{0, 1, 2, 3, 4}, {0, 2, 1, 3, 2}, "#000", "s"};
        const auto ps = paths(svgLinePlot({s}, "t", "x", "y", W, H));
        QCOMPARE(ps.size(), size_t(1));
        const std::vector<PathCmd>& c = ps[0];
        QCOMPARE(c.size(), s.x.size());
        QCOMPARE(c[0].op, 'M');
        for (size_t i = 1; i < c.size(); ++i) QCOMPARE(c[i].op, 'L');
        const double tol = 0.051;  // coordinates are written with one decimal
        QVERIFY(std::abs(c.front().x - f.left) < tol);
        QVERIFY(std::abs(c.back().x - f.right) < tol);
        const double width = f.right - f.left, height = f.bottom - f.top;
        for (size_t i = 0; i < c.size(); ++i) {
            QVERIFY(std::abs(c[i].x - (f.left + s.x[i] / 4.0 * width)) < tol);
            QVERIFY(c[i].y >= f.top && c[i].y <= f.bottom);
        }
        // y = 3 (max) and y = 0 (min) sit 5 % of the data range inside the frame's top and bottom.
        const double span = 3.0 * 1.1;
        QVERIFY(std::abs(c[3].y - (f.top + 0.15 / span * height)) < tol);
        QVERIFY(std::abs(c[0].y - (f.bottom - 0.15 / span * height)) < tol);
        // Linear in y: y = 1 and y = 2 a third and two thirds of the way from y = 0 to y = 3.
        QVERIFY(std::abs(c[2].y - (c[0].y + (c[3].y - c[0].y) / 3.0)) < 2 * tol);
        QVERIFY(std::abs(c[1].y - (c[0].y + 2.0 * (c[3].y - c[0].y) / 3.0)) < 2 * tol);
        QVERIFY(c[1].y < c[2].y);  // higher value, higher on the page
    }

    // A NaN (or infinite) x or y is not drawn and lifts the pen: the next finite point starts a
    // new stroke ('M'). The non-finite values neither reach the path nor stretch the axes.
    void nonFinitePointsBreakTheLine() {
        const int W = 640, H = 300;
        const Frame f = frameOf(W, H);
        const SvgSeries s{{0, 1, 2, 3, 4, 5, 6, kNaN, 8}, {0, 1, kNaN, 3, 4, kInf, 6, 7, 8}, "#000", "gaps"};
        const std::string svg = svgLinePlot({s}, "gaps", "x", "y", W, H);
        const auto ps = paths(svg);
        QCOMPARE(ps.size(), size_t(1));
        std::string ops;
        for (const PathCmd& c : ps[0]) ops += c.op;
        QCOMPARE(ops, std::string("MLMLMM"));  // points 0 1 | 3 4 | 6 | 8
        for (const PathCmd& c : ps[0]) {
            QVERIFY(std::isfinite(c.x) && std::isfinite(c.y));
            QVERIFY(c.x >= f.left - 0.05 && c.x <= f.right + 0.05 && c.y >= f.top && c.y <= f.bottom);
        }
        QVERIFY(std::abs(ps[0].back().x - f.right) < 0.051);  // x = 8 is the right edge: inf/NaN did not widen it
        const std::regex bad("nan|inf", std::regex::icase);
        QVERIFY(!std::regex_search(svg, bad));
        // A series with no finite point: an empty stroke and its legend entry, nothing else.
        const SvgSeries none{{0, 1}, {kNaN, kNaN}, "#111", "empty"};
        const std::string svg2 = svgLinePlot({none, s}, "t", "x", "y", W, H);
        QVERIFY(has(svg2, "<path d=\"\""));
        QVERIFY(has(svg2, ">empty</text>"));
        QVERIFY(!std::regex_search(svg2, bad));
        QVERIFY2(tagProblem(svg2).empty(), tagProblem(svg2).c_str());
    }

    // Data whose x does not vary (one time or one velocity repeated) must still be drawn inside
    // the frame, as data constant in y are.
    void constantXStaysInsideTheFrame() {
        const int W = 640, H = 300;
        const Frame f = frameOf(W, H);
        const SvgSeries s{{5, 5, 5}, {1, 2, 3}, "#000", "vertical"};
        const auto ps = paths(svgLinePlot({s}, "t", "x", "y", W, H));
        QCOMPARE(ps.size(), size_t(1));
        QCOMPARE(ps[0].size(), size_t(3));
        // Constant x is centred like constant y (the range is widened to x ± 1); it once fell
        // back to [0, 1] whatever the value, and x = 5 was drawn at 70 + 5·555 = 2845 px, far
        // right of the 640 px plot.
        for (const PathCmd& c : ps[0])
            QVERIFY2(std::abs(c.x - 0.5 * (f.left + f.right)) < 0.051, qPrintable(QString::number(c.x)));
        // Constant y, for comparison: inside the frame, in its middle.
        const SvgSeries flat{{0, 1, 2}, {7, 7, 7}, "#000", "flat"};
        const auto pf = paths(svgLinePlot({flat}, "t", "x", "y", W, H));
        for (const PathCmd& c : pf[0]) QVERIFY(std::abs(c.y - 0.5 * (f.top + f.bottom)) < 0.051);
    }

    // A complete document: doctype, head, one body, tags balanced, closed at the end; it names
    // the effect added and the candidates' verdicts (the trade-off with η and its correlation),
    // and shows the numbers it was given in the cells they belong to.
    void pageShowsTheResultItWasGiven() {
        const IdentifyResult r = handMadeResult();
        const std::string page = renderHtmlReport(r);
        QVERIFY(page.rfind("<!DOCTYPE html>\n<html><head>", 0) == 0);
        QVERIFY(page.size() > 15 && page.compare(page.size() - 15, 15, "</body></html>\n") == 0);
        for (const char* once : {"<html>", "</html>", "<head>", "</head>", "<body>", "</body>", "<title>"})
            QVERIFY2(count(page, once) == 1, once);
        const std::string problem = tagProblem(page);
        QVERIFY2(problem.empty(), problem.c_str());
        QVERIFY(has(page, "Set-up: prescribed, residual: prescribed. 137 fits, 12.3 s."));
        QVERIFY(has(page, "Effects added: <b>frictional_lag</b>"));
        QVERIFY(has(page, "<tr><td class=l>before (baseline)</td><td>0.1234</td><td>0.2345</td></tr>"));
        QVERIFY(has(page, "<tr><td class=l>after</td><td>0.05671</td><td>0.06782</td></tr>"));
        QVERIFY(has(page, "<tr><td class=l>run_01.csv</td><td class=l>fit</td><td>0.1111</td><td>0.2222</td>"
                          "<td>0.03333</td><td>0.04444</td></tr>"));
        QVERIFY(has(page, "<td class=l>frictional_lag</td><td class=l>frictional_lag.tau_s</td><td>0.01234</td>"
                          "<td>0.00056</td><td>-42.5</td><td class=l>dF/dt 0.612; </td>"));
        QVERIFY(has(page, "<td class=l>added</td></tr>"));
        QVERIFY(has(page, "<td class=l>backlash</td><td>1</td><td>3.2</td>"));
        QVERIFY(has(page, "<td class=l>dBIC = 3.2 is not below -10; its size trades off with the baseline's eta "
                          "(correlation 0.987): the data cannot tell the two apart</td>"));
        QVERIFY(has(page, "<tr><td class=l>mu</td><td>0.3125</td><td>0.0021</td></tr>"));
        QVERIFY(has(page, "<tr><td class=l>eta</td><td>1.75</td><td>&ndash;</td></tr>"));  // NaN stderr
        QVERIFY(has(page, "<tr><td class=l>mu</td><td>0.3126</td><td>0.0019</td></tr>"));
        QVERIFY(has(page, "<tr><td class=l>dF/dt</td><td>0.612</td><td>0.021</td></tr>"));
        QVERIFY(has(page, "forcing harmonics at 2.5 Hz multiples"));
        QVERIFY(has(page, "<h3>run_01.csv</h3>"));
        // Two diagnostics plots and three per run (force, residual, loops).
        QCOMPARE(count(page, "<svg "), size_t(5));
        QCOMPARE(count(page, "</svg>"), size_t(5));
        QVERIFY(!std::regex_search(page, std::regex(">-?(nan|inf)<", std::regex::icase)));
        QVERIFY(has(page, "No unexplained structure"));
        QVERIFY(!has(page, "Recovery self-test"));  // it did not run
        // The timeline, one row per stage, its label escaped.
        QVERIFY(has(page, "<h2>Where the time went</h2>"));
        QVERIFY(has(page, "<tr><td class=l>baseline</td><td>0.0</td><td>4.5</td><td>130</td></tr>"));
        QVERIFY(has(page, "<tr><td class=l>round 1: &lt;lag&gt;</td><td>4.6</td><td>7.7</td><td>7</td></tr>"));
    }

    // The verdict's evidence: one row per held-out run (its file, d before and after, the feature
    // the other runs chose, "none" where none predicted), the tests' summary; no section when the
    // test did not run (fewer than two runs, as in the handmade result).
    void structureTableShowsEachHeldOutRun() {
        IdentifyResult r = handMadeResult();
        QVERIFY(!has(renderHtmlReport(r), "Run-to-run structure"));
        r.traces.push_back(r.traces.front());
        r.traces[1].file = "run_<2>.csv";
        StructureTest& b = r.diagnosticsBefore.structure;
        b.runs = 2;
        b.logRatios = {0.25, -0.1};
        b.chosen = {"tN (line per sign)", ""};
        b.test.meanLogRatio = 0.075;
        b.test.midP = 0.5;
        StructureTest& a = r.diagnosticsAfter.structure;
        a.runs = 2;
        a.logRatios = {-0.01, -0.02};
        a.chosen = {"signV (3 bins)", "V (12 bins)"};
        a.test.meanLogRatio = -0.015;
        a.test.midP = 0.875;
        const std::string page = renderHtmlReport(r);
        QVERIFY(has(page, "<h3>Run-to-run structure</h3>"));
        QVERIFY(has(page, "Before: mean d 0.075, sign-flip mid-p 0.5; after: mean d -0.015, sign-flip mid-p 0.875."));
        QVERIFY(has(page, "<tr><td class=l>run_01.csv</td><td>0.250</td><td class=l>tN (line per sign)</td><td>-0.010</td>"
                          "<td class=l>signV (3 bins)</td></tr>"));
        QVERIFY(has(page, "<tr><td class=l>run_&lt;2&gt;.csv</td><td>-0.100</td><td class=l>none</td><td>-0.020</td>"
                          "<td class=l>V (12 bins)</td></tr>"));
        const std::string problem = tagProblem(page);
        QVERIFY2(problem.empty(), problem.c_str());
    }

    // An added effect's law-step check (AddedEffect::LawStepGain): the shares of the fit's sum
    // of squares it removes at the law's step and at the finer one, in its rows of the table and
    // in the JSON, and the sentence the CLI and the Identify panel show (lawStepText); a dash, no
    // JSON key and no sentence when unchecked (the handmade result's default).
    void lawStepGainIsShownWhereChecked() {
        IdentifyResult r = handMadeResult();
        QVERIFY(has(renderHtmlReport(r), "<td class=l>dF/dt 0.612; </td><td>&ndash;</td></tr>"));
        QVERIFY(!toJson(r)["effects_added"][0].contains("law_step_check"));
        QVERIFY(lawStepText(r.effectsAdded[0]).empty());
        r.effectsAdded[0].lawStep = {8, 10.0, 8.0, 9.0, 8.55};
        QCOMPARE(lawStepText(r.effectsAdded[0]),
                 std::string("removes 20.0 % of the fit's sum of squares at the law's step, 5.0 % with every law step split in 8"));
        QVERIFY(has(renderHtmlReport(r), "<td class=l>dF/dt 0.612; </td><td>20.0 % / 5.0 % (&times;8)</td></tr>"));
        const nlohmann::json j = toJson(r)["effects_added"][0]["law_step_check"];
        QCOMPARE(j["refinement"].get<int>(), 8);
        QCOMPARE(j["gain"].get<double>(), 0.2);
        QVERIFY(std::abs(j["gain_refined"].get<double>() - 0.05) < 1e-12);
        QCOMPARE(j["fit_ss_after_refined"].get<double>(), 8.55);
    }

    // An unresolved law channel (LawResolution) is its own warning when the residual is otherwise
    // white, with the same words as the JSON's and the CLI's lawResolutionText; nothing when resolved.
    void pageWarnsOfAnUnresolvedLawChannel() {
        IdentifyResult r = handMadeResult();
        QVERIFY(!r.unexplained);
        r.lawResolution.checked = true;
        r.lawResolution.refinement = 8;
        r.lawResolution.runs = {{"run_01.csv", 0.2, 0.05}};
        const std::string page = renderHtmlReport(r);
        QVERIFY(has(page, "<p class=\"warn\">Numerical resolution: " + htmlEscape(lawResolutionText(r.lawResolution)) + ".</p>"));
        QVERIFY(tagProblem(page).empty());
        r.lawResolution.runs[0].change_N = 0.01;
        QVERIFY(!has(renderHtmlReport(r), "Numerical resolution"));
    }

    // The selection rule is one text (selectionRule) with the settings the result was run with:
    // the HTML candidates table and the JSON report's selection.criterion give the same words.
    void ruleTextIsTheOneTheJsonGives() {
        IdentifyResult r = handMadeResult();
        r.heldOutAlpha = 0.01;
        r.minHeldOutGain = 0.07;
        const std::string rule = selectionRule(r);
        QVERIFY2(has(rule, "one-sided p < 0.01"), rule.c_str());
        QVERIFY2(has(rule, "at least 7 % of the held-out MSE"), rule.c_str());
        QVERIFY(has(renderHtmlReport(r), htmlEscape(rule)));
        QCOMPARE(toJson(r)["selection"]["criterion"].get<std::string>(), rule);
        QCOMPARE(toJson(r)["selection"]["min_held_out_gain"].get<double>(), 0.07);
    }

    // Strings that come from outside the program (run file names, notes and reasons that quote
    // them) appear escaped: a run called <script>… cannot inject markup into the report.
    void pageEscapesUserStrings() {
        IdentifyResult r = handMadeResult();
        const std::string evil = "<script>alert(\"x\")</script>&.csv";
        const std::string shown = "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt;&amp;.csv";
        r.before.runs[0].file = r.after.runs[0].file = r.traces[0].file = evil;
        r.setup = "prescribed <i>";
        r.baselineNote = "kept: p < 0.05 & \"restart\"";
        r.unexplained = true;
        r.unexplainedReason = "<b>structure</b> at 2f";
        r.candidates[1].reason = "held-out p = 0.3 > 0.05";
        r.selfTest.ran = true;
        r.selfTest.ok = false;
        r.selfTest.message = "<img src=x onerror=alert(1)>";
        const std::string page = renderHtmlReport(r);
        QVERIFY(!has(page, "<script") && !has(page, "<img") && !has(page, "<i>") && !has(page, "<b>structure"));
        QCOMPARE(count(page, shown), size_t(2));  // the per-run table and the run's heading
        QVERIFY(has(page, "Set-up: prescribed &lt;i&gt;,"));
        QVERIFY(has(page, "Baseline: kept: p &lt; 0.05 &amp; &quot;restart&quot;."));
        QVERIFY(has(page, "Unexplained structure remains: &lt;b&gt;structure&lt;/b&gt; at 2f"));
        QVERIFY(!has(page, "No unexplained structure"));
        QVERIFY(has(page, "held-out p = 0.3 &gt; 0.05; its size trades off"));
        QVERIFY(has(page, "<h3>Recovery self-test</h3><p>Not completed: &lt;img src=x onerror=alert(1)&gt;</p>"));
        const std::string problem = tagProblem(page);
        QVERIFY2(problem.empty(), problem.c_str());
    }

    // The recovery self-test's table when it ran to the end: one row per effect with its size,
    // detections out of replicas and what it was confused with; and the false alarms.
    void pageShowsTheSelfTestWhenItRan() {
        IdentifyResult r = handMadeResult();
        SelfTestResult& st = r.selfTest;
        st.ran = st.ok = true;
        st.noiseRms = 0.0321;
        st.neff = 480;
        st.falseAlarmReplicas = 20;
        st.falseAlarms = 1;
        SelfTestRow row;
        row.effect = "backlash";
        row.sizeParam = "backlash.halfWidth_m";
        row.size = 5e-5;
        row.unit = "m";
        row.snr = 1.25;
        row.visibleSnr = 0.75;
        row.replicas = 10;
        row.detected = 7;
        row.confused = 2;
        row.missed = 1;
        row.confusedWith = {{"frictional_lag", 2}};
        row.note = "size < bound";
        st.rows = {row};
        const std::string page = renderHtmlReport(r);
        QVERIFY(has(page, "<h3>Recovery self-test</h3>"));
        QVERIFY(has(page, "(RMS 0.0321)"));
        QVERIFY(has(page, "n<sub>eff</sub> 480"));
        QVERIFY(has(page, "False alarms on 20 replicas without an effect: <b>1</b>."));
        QVERIFY(has(page, "<tr><td class=l>backlash</td><td>backlash.halfWidth_m = 5e-05 m</td><td>1.25</td><td>0.75</td>"
                          "<td>7/10</td><td>2 (frictional_lag &times;2)</td><td>1</td><td class=l>size &lt; bound</td></tr>"));
        const std::string problem = tagProblem(page);
        QVERIFY2(problem.empty(), problem.c_str());
    }
};

QTEST_APPLESS_MAIN(TstReportHtml)
#include "tst_report_html.moc"
