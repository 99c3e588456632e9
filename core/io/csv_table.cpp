#include "csv_table.hpp"

#include "atomic_file.hpp"

#include <csv.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace stickslip::io {

std::string CsvError::what() const {
    std::ostringstream s;
    s << (file.empty() ? std::string("<input>") : file);
    if (line > 0) {
        s << ':' << line;
        if (column > 0) s << ':' << column;
    }
    s << ": " << message;
    return s.str();
}

int CsvTable::column(const std::string& name) const {
    for (size_t j = 0; j < header.size(); ++j)
        if (header[j] == name) return static_cast<int>(j);
    return -1;
}

long CsvTable::cellColumn(size_t row, size_t col) const {
    const size_t k = row * header.size() + col;
    return col < header.size() && k < cellColumns.size() ? cellColumns[k] : 0;
}

size_t CsvTable::rows() const { return columns.empty() ? 0 : columns.front().size(); }

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string trim(std::string_view s) {
    size_t b = 0, e = s.size();
    while (b < e && (isBlank(s[b]) || s[b] == '\n')) ++b;
    while (e > b && (isBlank(s[e - 1]) || s[e - 1] == '\n')) --e;
    return std::string(s.substr(b, e - b));
}

// One cell as libcsv hands it over, with the 1-based character column where it starts.
struct Field {
    std::string text;
    long column = 1;
};

// Splits one physical line into fields with libcsv. libcsv does not report positions, so
// the line is fed one byte at a time: a field-end callback fires while the delimiter that
// ends it is being consumed, which tells where the next field starts. Lines are parsed
// one at a time (a numeric table has no quoted line breaks), so line numbers are exact.
class LineSplitter {
public:
    explicit LineSplitter(char delimiter) {
        csv_init(&parser_, CSV_STRICT | CSV_STRICT_FINI | CSV_APPEND_NULL);
        csv_set_delim(&parser_, static_cast<unsigned char>(delimiter));
    }
    ~LineSplitter() { csv_free(&parser_); }
    LineSplitter(const LineSplitter&) = delete;
    LineSplitter& operator=(const LineSplitter&) = delete;

    // Fills `fields`; on a quoting error returns false with the 1-based column in errColumn.
    bool split(std::string_view line, std::vector<Field>& fields, long& errColumn) {
        fields_ = &fields;
        fields.clear();
        nextStart_ = 1;
        for (size_t i = 0; i < line.size(); ++i) {
            pos_ = static_cast<long>(i) + 1;
            if (csv_parse(&parser_, &line[i], 1, &LineSplitter::onField, &LineSplitter::onRow, this) != 1) {
                errColumn = pos_;
                reset();
                return false;
            }
        }
        pos_ = static_cast<long>(line.size()) + 1;
        if (csv_fini(&parser_, &LineSplitter::onField, &LineSplitter::onRow, this) != 0) {
            errColumn = pos_;
            reset();
            return false;
        }
        // libcsv reports nothing for an empty line; we keep one empty field so that the
        // caller can say "empty" at column 1.
        if (fields.empty()) fields.push_back({std::string(), 1});
        return true;
    }

private:
    static void onField(void* s, size_t len, void* self) {
        auto* me = static_cast<LineSplitter*>(self);
        me->fields_->push_back({s ? std::string(static_cast<const char*>(s), len) : std::string(), me->nextStart_});
        me->nextStart_ = me->pos_ + 1;
    }
    static void onRow(int, void*) {}
    void reset() {
        csv_free(&parser_);
        const unsigned char delim = csv_get_delim(&parser_);
        csv_init(&parser_, CSV_STRICT | CSV_STRICT_FINI | CSV_APPEND_NULL);
        csv_set_delim(&parser_, delim);
    }

    csv_parser parser_{};
    std::vector<Field>* fields_ = nullptr;
    long pos_ = 0;
    long nextStart_ = 1;
};

// Comma, semicolon or tab, whichever occurs most often outside quotes in the header.
char detectDelimiter(std::string_view headerLine) {
    size_t comma = 0, semi = 0, tab = 0;
    bool quoted = false;
    for (char c : headerLine) {
        if (c == '"') quoted = !quoted;
        if (quoted) continue;
        if (c == ',') ++comma;
        if (c == ';') ++semi;
        if (c == '\t') ++tab;
    }
    if (semi > comma && semi >= tab) return ';';
    if (tab > comma && tab > semi) return '\t';
    return ',';
}

// Locale-independent and strict: the whole trimmed cell must be one finite number.
bool parseNumber(const std::string& cell, double& v, std::string& why) {
    if (cell.empty()) {
        why = "empty cell";
        return false;
    }
    const char* b = cell.data();
    const char* e = b + cell.size();
    if (*b == '+') ++b;  // from_chars does not take a leading '+'
    const auto [ptr, ec] = std::from_chars(b, e, v);
    if (ec == std::errc::result_out_of_range) {
        why = "number out of range '" + cell + "'";
        return false;
    }
    if (ec != std::errc() || ptr != e) {
        why = "not a number: '" + cell + "'";
        return false;
    }
    if (!std::isfinite(v)) {
        why = "non-finite value '" + cell + "'";
        return false;
    }
    return true;
}

}  // namespace

bool parseCsvTable(const std::string& text, const std::string& nameForErrors, CsvTable& out, CsvError& err) {
    CsvTable t;
    t.path = nameForErrors;
    auto fail = [&](long line, long column, std::string message) {
        err = CsvError{nameForErrors, line, column, std::move(message)};
        return false;
    };

    std::vector<Field> fields;
    std::unique_ptr<LineSplitter> splitter;
    long lineNo = 0;
    size_t begin = 0;
    while (begin < text.size()) {
        size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        std::string_view line(text.data() + begin, end - begin);
        begin = end + 1;
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (lineNo == 1 && line.size() >= 3 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 BOM

        size_t first = 0;
        while (first < line.size() && isBlank(line[first])) ++first;
        if (first == line.size()) continue;  // blank line
        if (line[first] == '#') {
            t.comments.push_back(trim(line.substr(first + 1)));
            continue;
        }

        if (!splitter) {
            t.delimiter = detectDelimiter(line);
            splitter = std::make_unique<LineSplitter>(t.delimiter);
        }
        long errColumn = 0;
        if (!splitter->split(line, fields, errColumn))
            return fail(lineNo, errColumn, "malformed quoting");

        if (t.header.empty()) {
            t.headerLine = lineNo;
            for (const Field& f : fields) {
                std::string name = trim(f.text);
                if (name.empty()) return fail(lineNo, f.column, "empty column name in header");
                for (const std::string& h : t.header)
                    if (h == name) return fail(lineNo, f.column, "duplicate column name '" + name + "'");
                t.header.push_back(std::move(name));
            }
            t.columns.assign(t.header.size(), {});
            continue;
        }

        if (fields.size() != t.header.size()) {
            const long col = fields.size() > t.header.size() ? fields[t.header.size()].column
                                                             : static_cast<long>(line.size()) + 1;
            return fail(lineNo, col,
                        "expected " + std::to_string(t.header.size()) + " fields as in the header (line " +
                            std::to_string(t.headerLine) + "), found " + std::to_string(fields.size()));
        }
        for (size_t j = 0; j < fields.size(); ++j) {
            double v = 0;
            std::string why;
            // Column of the first non-blank character of the cell.
            long col = fields[j].column;
            const std::string cell = trim(fields[j].text);
            if (!parseNumber(cell, v, why))
                return fail(lineNo, col, why + " in column '" + t.header[j] + "'");
            t.columns[j].push_back(v);
            t.cellColumns.push_back(col <= INT32_MAX ? static_cast<std::int32_t>(col) : 0);
        }
        t.rowLines.push_back(lineNo);
    }
    if (t.header.empty()) return fail(lineNo > 0 ? lineNo : 1, 1, "no header line (file is empty or only comments)");
    out = std::move(t);
    return true;
}

bool readCsvTable(const std::string& path, CsvTable& out, CsvError& err) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        err = CsvError{path, 0, 0, std::string("cannot open: ") + std::strerror(errno)};
        return false;
    }
    std::ostringstream buf;
    buf << in.rdbuf();
    if (in.bad()) {
        err = CsvError{path, 0, 0, std::string("read error: ") + std::strerror(errno)};
        return false;
    }
    return parseCsvTable(buf.str(), path, out, err);
}

bool writeFileAtomically(const std::string& path, const std::string& content, std::string* error) {
    AtomicFileWriter f(path);
    if (f.open() && f.write(content) && f.commit()) return true;
    if (error) *error = f.error();
    return false;
}

}  // namespace stickslip::io
