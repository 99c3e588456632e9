#include "run_csv.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <cstdio>

#include "../version.hpp"
#include "channel_ranges.hpp"
#include "units.hpp"
#include "atomic_file.hpp"

namespace stickslip::io {

const std::vector<std::string>& runCsvColumns() {
    static const std::vector<std::string> cols = {"time_s",           "stage_disp_m",   "slider_disp_m",
                                                  "slider_vel_mps",   "rel_vel_mps",    "friction_force_N",
                                                  "friction_ratio",   "state_alpha",    "stuck"};
    return cols;
}

std::vector<std::vector<double>> runCsvValues(const RunResult& r) {
    std::vector<std::vector<double>> cols(runCsvColumns().size());
    for (auto& c : cols) c.reserve(r.samples.size());
    for (const Sample& x : r.samples) {
        const double row[] = {x.t_s,     x.stage_m, x.slider_m, x.sliderVel_mps,      x.relVel_mps,
                              x.force_N, x.ratio,   x.alpha,    x.stuck ? 1.0 : 0.0};
        for (size_t j = 0; j < cols.size(); ++j) cols[j].push_back(row[j]);
    }
    return cols;
}

namespace {

// The '#' lines and the header of a run file.
std::string runCsvHead(const SimParams& p, const RunResult& r, const std::vector<std::string>& extraComments) {
    std::string s;
    s += std::string("# StickSlip Lab ") + kVersion + " run\n";
    s += std::string("# version = ") + kVersion + "\n";
    s += std::string("# model = ") + toString(p.law) + "\n";
    s += std::string("# setup = ") + toString(p.setup) + "\n";
    s += std::string("# status = ") + toString(r.status) + "\n";
    if (!r.message.empty()) {
        std::string msg = r.message;
        for (char& c : msg)
            if (c == '\n' || c == '\r') c = ' ';
        s += "# message = " + msg + "\n";
    }
    // Every key; a shared law key (μ, ε_T, D_c) reads the selected law's own value.
    for (const std::string& key : paramKeys()) {
        double v = 0;
        if (!getParam(p, key, v)) continue;
        std::string unit;
        paramUnit(key, unit);
        // Shortest text that reads back to the same double.
        char num[64];
        const auto res = std::to_chars(num, num + sizeof num, v, std::chars_format::general);
        s += "# " + key + " = " + std::string(num, res.ptr) + (unit.empty() ? "" : " ") + unit + "\n";
    }
    for (const std::string& c : extraComments) s += "# " + c + "\n";
    const auto& cols = runCsvColumns();
    for (size_t j = 0; j < cols.size(); ++j) s += (j ? "," : "") + cols[j];
    s += '\n';
    return s;
}

void appendRow(std::string& s, const Sample& x) {
    char buf[512];
    const int n = std::snprintf(buf, sizeof buf, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d\n", x.t_s,
                                x.stage_m, x.slider_m, x.sliderVel_mps, x.relVel_mps, x.force_N, x.ratio, x.alpha,
                                x.stuck ? 1 : 0);
    s.append(buf, static_cast<size_t>(n));
}

}  // namespace

std::string runCsvText(const SimParams& p, const RunResult& r, const std::vector<std::string>& extraComments) {
    std::string s = runCsvHead(p, r, extraComments);
    s.reserve(s.size() + r.samples.size() * 150);
    for (const Sample& x : r.samples) appendRow(s, x);
    return s;
}

bool writeRunCsv(const std::string& path, const SimParams& p, const RunResult& r, std::string* error,
                 const std::vector<std::string>& extraComments) {
    // Streamed in blocks: the text of a long run (about 130 bytes per sample) is never held
    // whole in memory next to its samples.
    constexpr size_t kBlock = 1 << 20;
    AtomicFileWriter f(path);
    bool ok = f.open() && f.write(runCsvHead(p, r, extraComments));
    std::string block;
    block.reserve(kBlock + 512);
    for (size_t i = 0; ok && i < r.samples.size(); ++i) {
        appendRow(block, r.samples[i]);
        if (block.size() >= kBlock || i + 1 == r.samples.size()) {
            ok = f.write(block);
            block.clear();
        }
    }
    if (ok && f.commit()) return true;
    if (error) *error = f.error();
    return false;
}

namespace {
constexpr size_t kStreamBlock = 1 << 20;
}

RunCsvStream::RunCsvStream(std::string path) : path_(std::move(path)) {}

RunCsvStream::~RunCsvStream() {
    if (rowsFd_ >= 0) ::close(rowsFd_);
}

bool RunCsvStream::open(std::string* error) {
    const size_t slash = path_.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path_.substr(0, slash));
    // Unnamed (O_TMPFILE) where the file system allows, else named and unlinked at once.
    rowsFd_ = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (rowsFd_ < 0) {
        std::string tmpl = path_ + ".rows.XXXXXX";
        rowsFd_ = ::mkstemp(tmpl.data());
        if (rowsFd_ >= 0) ::unlink(tmpl.c_str());
    }
    if (rowsFd_ < 0) {
        if (error) *error = path_ + ": cannot create temporary file: " + std::strerror(errno);
        return false;
    }
    block_.reserve(kStreamBlock + 512);
    return true;
}

bool RunCsvStream::flush() {
    const char* p = block_.data();
    size_t left = block_.size();
    while (left > 0 && error_.empty()) {
        const ssize_t n = ::write(rowsFd_, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) error_ = path_ + ": write failed: " + std::strerror(errno);
        else { p += n; left -= static_cast<size_t>(n); }
    }
    block_.clear();
    return error_.empty();
}

void RunCsvStream::add(const Sample& x) {
    if (rowsFd_ < 0 || !error_.empty()) return;
    appendRow(block_, x);
    if (block_.size() >= kStreamBlock) flush();
}

bool RunCsvStream::finish(const SimParams& p, const RunResult& r, std::string* error,
                          const std::vector<std::string>& extraComments) {
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return false;
    };
    if (rowsFd_ < 0) return fail(path_ + ": not open for writing");
    if (!flush()) return fail(error_);
    AtomicFileWriter f(path_);
    if (!f.open() || !f.write(runCsvHead(p, r, extraComments))) return fail(f.error());
    if (::lseek(rowsFd_, 0, SEEK_SET) != 0) return fail(path_ + ": cannot read back the rows: " + std::strerror(errno));
    std::string buf(kStreamBlock, '\0');
    for (;;) {
        const ssize_t n = ::read(rowsFd_, buf.data(), buf.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return fail(path_ + ": cannot read back the rows: " + std::strerror(errno));
        if (n == 0) break;
        if (!f.write(std::string_view(buf.data(), static_cast<size_t>(n)))) return fail(f.error());
    }
    if (!f.commit()) return fail(f.error());
    return true;
}

bool slipHistoryFromTable(const CsvTable& t, SlipHistory& out, CsvError& err) {
    auto fail = [&](long line, long column, std::string msg) {
        err = CsvError{t.path, line, column, std::move(msg)};
        return false;
    };
    std::string names;
    for (const std::string& h : t.header) names += (names.empty() ? "" : ", ") + h;
    const int it = t.column("time_s");
    if (it < 0) return fail(t.headerLine, 1, "missing column 'time_s' (columns: " + names + ")");
    const int ig = t.column("rel_disp_m");
    const int iu = t.column("stage_disp_m");
    const int iv = t.column("rel_vel_mps");
    const int in = t.column("normal_force_N");
    if (ig < 0 && iu < 0 && iv < 0)
        return fail(t.headerLine, 1,
                    "needs one of the columns 'rel_disp_m', 'stage_disp_m' or 'rel_vel_mps' (columns: " + names + ")");
    if (t.rows() < 2) return fail(t.headerLine, 1, "a slip history needs at least two data rows");

    // Every column the history uses, against the one table of physical ranges
    // (channel_ranges.hpp); time also strictly increasing.
    auto check = [&](int j, Channel c) {
        if (j < 0) return true;
        ValueProblem bad;
        const auto col = static_cast<size_t>(j);
        if (checkChannel(c, t.header[col], t.columns[col], bad)) return true;
        return fail(t.rowLines[bad.row], t.cellColumn(bad.row, col), bad.message);
    };
    if (!check(it, Channel::Time) || !check(ig, Channel::Displacement) || !check(iu, Channel::Displacement) ||
        !check(iv, Channel::Velocity) || !check(in, Channel::NormalForce))
        return false;
    if (in >= 0) {
        const std::vector<double>& tn = t.columns[static_cast<size_t>(in)];
        for (size_t i = 0; i < tn.size(); ++i)
            if (!(tn[i] > 0.0)) {
                char buf[200];
                std::snprintf(buf, sizeof buf, "normal_force_N must be > 0, is %.10g", tn[i]);
                return fail(t.rowLines[i], t.cellColumn(i, static_cast<size_t>(in)), buf);
            }
    }

    SlipHistory h;
    if (ig >= 0 || iu >= 0) {
        h = SlipHistory::fromSlip(t.columns[static_cast<size_t>(it)], t.columns[static_cast<size_t>(ig >= 0 ? ig : iu)]);
        if (iv >= 0) h.velocity_mps = t.columns[static_cast<size_t>(iv)];
    } else {
        h = SlipHistory::fromVelocity(t.columns[static_cast<size_t>(it)], t.columns[static_cast<size_t>(iv)], 0.0);
        // Velocities and times in range can still integrate to a slip out of range.
        ValueProblem bad;
        if (!checkChannel(Channel::Displacement, "slip integrated from rel_vel_mps", h.slip_m, bad))
            return fail(t.rowLines[bad.row], t.cellColumn(bad.row, static_cast<size_t>(iv)), bad.message);
    }
    if (in >= 0) h.normalForce_N = t.columns[static_cast<size_t>(in)];
    const std::string problem = formatIssues(h.validate());
    if (!problem.empty()) return fail(0, 0, problem);
    out = std::move(h);
    return true;
}

bool readSlipHistoryCsv(const std::string& path, SlipHistory& out, CsvError& err) {
    CsvTable t;
    if (!readCsvTable(path, t, err)) return false;
    return slipHistoryFromTable(t, out, err);
}

}  // namespace stickslip::io
