#include "cell_records.hpp"

#include <cerrno>
#include <cinttypes>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace stickslip::cli {

namespace {

// Raw little helpers: values are memcpy'd, so a double crosses as its exact bit pattern.
struct Writer {
    std::string out;
    template <class T>
    void put(T v) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        out.append(b, sizeof(T));
    }
    void putVec(const std::vector<double>& v) {
        put<std::uint64_t>(v.size());
        out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
    }
    void putStr(const std::string& s) {
        put<std::uint64_t>(s.size());
        out += s;
    }
};

struct Reader {
    const std::string& in;
    std::size_t pos = 0;
    bool ok = true;
    template <class T>
    T get() {
        T v{};
        if (pos + sizeof(T) > in.size()) { ok = false; return v; }
        std::memcpy(&v, in.data() + pos, sizeof(T));
        pos += sizeof(T);
        return v;
    }
    std::size_t count(std::size_t elemSize) {
        const auto n = get<std::uint64_t>();
        if (!ok || n > (in.size() - pos) / elemSize) { ok = false; return 0; }
        return static_cast<std::size_t>(n);
    }
    void getVec(std::vector<double>& v) {
        v.resize(count(sizeof(double)));
        if (!v.empty()) std::memcpy(v.data(), in.data() + pos, v.size() * sizeof(double));
        pos += v.size() * sizeof(double);
    }
    void getStr(std::string& s) {
        s.assign(in, pos, count(1));
        pos += s.size();
    }
};

}  // namespace

std::string encodeMapCell(const MapCell& c) {
    Writer w;
    w.put<std::uint64_t>(c.index);
    w.put<std::int32_t>(static_cast<std::int32_t>(c.status));
    w.put<std::int32_t>(static_cast<std::int32_t>(c.motion));
    w.put<std::int32_t>(c.period);
    w.put(c.stickFraction);
    w.put(c.maxRelVel_mps);
    w.putStr(c.message);
    return std::move(w.out);
}

bool decodeMapCell(const std::string& bytes, MapCell& c) {
    Reader r{bytes};
    c.index = static_cast<std::size_t>(r.get<std::uint64_t>());
    c.status = static_cast<RunStatus>(r.get<std::int32_t>());
    c.motion = static_cast<MotionClass>(r.get<std::int32_t>());
    c.period = r.get<std::int32_t>();
    c.stickFraction = r.get<double>();
    c.maxRelVel_mps = r.get<double>();
    r.getStr(c.message);
    return r.ok && r.pos == bytes.size();
}

std::string encodeSweepValue(const SweepValueRecord& rec) {
    Writer w;
    const SweepPoint& p = rec.point;
    const PoincareSection& s = p.section;
    w.put<std::uint64_t>(rec.index);
    w.put<std::uint8_t>(rec.done ? 1 : 0);
    w.put(p.value);
    w.put<std::int32_t>(p.direction);
    w.put(s.period_s);
    for (const auto* v : {&s.t_s, &s.slider_m, &s.relVel_mps, &s.ratio, &s.alpha}) w.putVec(*v);
    w.put(s.stickFraction);
    w.put(s.maxRelVel_mps);
    w.put<std::int64_t>(s.slipSteps);
    w.put<std::int32_t>(static_cast<std::int32_t>(s.status));
    w.putStr(s.message);
    const Classification& c = p.classification;
    w.put<std::int32_t>(static_cast<std::int32_t>(c.motion));
    w.put<std::int32_t>(c.period);
    w.put(c.stickFraction);
    w.put(c.maxRelVel_mps);
    w.put(c.bestMismatch);
    w.put(p.lyapunovPerCycle);
    w.put(p.lyapunovPerSecond);
    return std::move(w.out);
}

bool decodeSweepValue(const std::string& bytes, SweepValueRecord& rec) {
    Reader r{bytes};
    SweepPoint& p = rec.point;
    PoincareSection& s = p.section;
    rec.index = static_cast<std::size_t>(r.get<std::uint64_t>());
    rec.done = r.get<std::uint8_t>() != 0;
    p.value = r.get<double>();
    p.direction = r.get<std::int32_t>();
    s.period_s = r.get<double>();
    for (auto* v : {&s.t_s, &s.slider_m, &s.relVel_mps, &s.ratio, &s.alpha}) r.getVec(*v);
    s.stickFraction = r.get<double>();
    s.maxRelVel_mps = r.get<double>();
    s.slipSteps = static_cast<long>(r.get<std::int64_t>());
    s.status = static_cast<RunStatus>(r.get<std::int32_t>());
    r.getStr(s.message);
    Classification& c = p.classification;
    c.motion = static_cast<MotionClass>(r.get<std::int32_t>());
    c.period = r.get<std::int32_t>();
    c.stickFraction = r.get<double>();
    c.maxRelVel_mps = r.get<double>();
    c.bestMismatch = r.get<double>();
    p.lyapunovPerCycle = r.get<double>();
    p.lyapunovPerSecond = r.get<double>();
    return r.ok && r.pos == bytes.size();
}

std::string fingerprint(const std::string& text) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char ch : text) {
        h ^= ch;
        h *= 1099511628211ull;
    }
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
    return buf;
}

namespace {

std::string where(const std::string& path, std::size_t line) { return path + ":" + std::to_string(line) + ": "; }

}  // namespace

std::string formatMapCellLine(const MapCell& c) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "cell %zu %d %d %.17g %.17g", c.index, static_cast<int>(c.motion), c.period,
                  c.stickFraction, c.maxRelVel_mps);
    return buf;
}

bool parseMapCellLine(const std::string& line, std::size_t cells, MapCell& c) {
    unsigned long long index = 0;
    int motion = 0, period = 0, used = 0;
    double sf = 0, mrv = 0;
    if (std::sscanf(line.c_str(), "cell %llu %d %d %lg %lg%n", &index, &motion, &period, &sf, &mrv, &used) != 5 ||
        static_cast<std::size_t>(used) != line.size() || index >= cells || motion < 0 || motion > 2)
        return false;
    c = MapCell{};
    c.index = static_cast<std::size_t>(index);
    c.status = RunStatus::Ok;
    c.motion = static_cast<MotionClass>(motion);
    c.period = period;
    c.stickFraction = sf;
    c.maxRelVel_mps = mrv;
    return true;
}

std::string formatSweepValueLine(const SweepValueRecord& r) {
    static const char* hex = "0123456789abcdef";
    const std::string bytes = encodeSweepValue(r);
    std::string line = "value " + std::to_string(r.index) + " ";
    for (unsigned char b : bytes) {
        line += hex[b >> 4];
        line += hex[b & 15];
    }
    return line;
}

bool parseSweepValueLine(const std::string& line, std::size_t values, SweepValueRecord& r) {
    unsigned long long index = 0;
    int used = 0;
    if (std::sscanf(line.c_str(), "value %llu %n", &index, &used) != 1 || used == 0 || index >= values) return false;
    const std::size_t n = line.size() - static_cast<std::size_t>(used);
    if (n % 2 != 0) return false;
    std::string bytes(n / 2, '\0');
    auto nibble = [](char ch) { return ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10 : -1; };
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        const int hi = nibble(line[used + 2 * i]), lo = nibble(line[used + 2 * i + 1]);
        if (hi < 0 || lo < 0) return false;
        bytes[i] = static_cast<char>(hi * 16 + lo);
    }
    return decodeSweepValue(bytes, r) && r.index == index && r.done && r.point.section.ok();
}

namespace {

// Reads the complete lines of an existing checkpoint, passing each record line to accept();
// `complete` is the byte length up to and including the last newline (a torn last line is
// dropped).
bool readCheckpoint(const std::string& path, const std::string (&header)[3],
                    const std::function<bool(const std::string&)>& accept, const std::string& form,
                    std::uintmax_t& complete, std::string* error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) { *error = path + ": cannot read checkpoint: " + std::strerror(errno); return false; }
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const std::size_t lastNl = text.rfind('\n');
    complete = lastNl == std::string::npos ? 0 : lastNl + 1;
    std::size_t pos = 0, lineNo = 0;
    while (pos < complete) {
        const std::size_t nl = text.find('\n', pos);
        const std::string line = text.substr(pos, nl - pos);
        pos = nl + 1;
        ++lineNo;
        if (lineNo == 1 && line != header[0]) {
            *error = where(path, 1) + "not a checkpoint of this command (expected '" + header[0] + "')";
            return false;
        }
        if (lineNo <= 3 && line != header[lineNo - 1]) {
            *error = where(path, lineNo) + "checkpoint was written for other settings ('" + line +
                     "', this run needs '" + header[lineNo - 1] +
                     "'); use the original options, or delete the file or choose another --checkpoint";
            return false;
        }
        if (lineNo > 3 && !accept(line)) {
            *error = where(path, lineNo) + "malformed checkpoint record '" + line.substr(0, 80) +
                     (line.size() > 80 ? "…" : "") + "' (expected '" + form + "')";
            return false;
        }
    }
    if (complete > 0 && lineNo < 3) {
        *error = where(path, lineNo) + "checkpoint header is incomplete; delete the file to start afresh";
        return false;
    }
    return true;
}

}  // namespace

CheckpointLog::~CheckpointLog() {
    if (file_) std::fclose(file_);
}

bool CheckpointLog::open(const std::string& path, const std::string& kind, const std::string& fp,
                         const std::string& countLine, const std::function<bool(const std::string&)>& accept,
                         const std::string& form, std::string* error) {
    path_ = path;
    const std::string header[3] = {"# stickslip-cli " + kind + " checkpoint v1", "# fingerprint " + fp, "# " + countLine};
    std::error_code ec;
    std::uintmax_t complete = 0;
    const bool exists = std::filesystem::exists(path, ec);
    if (exists && !readCheckpoint(path, header, accept, form, complete, error)) return false;
    // Cut a torn last line, so the next record starts on a line of its own.
    if (exists && std::filesystem::file_size(path, ec) != complete) std::filesystem::resize_file(path, complete, ec);
    if (ec) { *error = path + ": cannot truncate the torn last line: " + ec.message(); return false; }
    file_ = std::fopen(path.c_str(), "ab");
    if (!file_) { *error = path + ": cannot open checkpoint for writing: " + std::strerror(errno); return false; }
    if (complete == 0) {
        std::fprintf(file_, "%s\n%s\n%s\n", header[0].c_str(), header[1].c_str(), header[2].c_str());
        if (std::fflush(file_) != 0) { *error = path + ": cannot write checkpoint: " + std::strerror(errno); return false; }
    }
    return true;
}

bool CheckpointLog::append(const std::string& line, std::string* error) {
    if (!file_) return true;
    std::fprintf(file_, "%s\n", line.c_str());
    if (std::fflush(file_) != 0) {
        *error = path_ + ": cannot write checkpoint: " + std::strerror(errno);
        return false;
    }
    return true;
}

}  // namespace stickslip::cli
