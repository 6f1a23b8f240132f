#include "cli/flags.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "util/error.h"

namespace strata::cli {

void badFlag(const std::string& what) { throw Error("strata: error: " + what); }

unsigned long parseUnsigned(const std::string& flag, const std::string& value, unsigned long min,
                            unsigned long max) {
    errno = 0;
    char* end = nullptr;
    const unsigned long v = std::strtoul(value.c_str(), &end, 10);
    if (value.empty() || value[0] == '-' || *end != '\0' || errno == ERANGE || v < min || v > max)
        badFlag(flag + " expects an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                "], got '" + value + "'");
    return v;
}

std::string numberText(double v) {
    if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

double parsePositive(const std::string& flag, const std::string& value, double max, const char* what) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !(v > 0.0) || v > max)
        badFlag(flag + " expects " + what + " in (0, " + numberText(max) + "], got '" + value + "'");
    return v;
}

double parseFinite(const std::string& flag, const std::string& value) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v))
        badFlag(flag + " expects a finite number, got '" + value + "'");
    return v;
}

// Three comma-separated numbers, each finite and in [lo, hi]; `expects`
// says what in the error.
glm::dvec3 parseTriple(const std::string& flag, const std::string& value, double lo, double hi,
                       const std::string& expects) {
    double c[3];
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = value.find(',', start);
        if ((k < 2) != (comma != std::string::npos)) badFlag(flag + " expects " + expects + ", got '" + value + "'");
        const std::string item = value.substr(start, k < 2 ? comma - start : std::string::npos);
        char* end = nullptr;
        c[k] = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(c[k]) || c[k] < lo || c[k] > hi)
            badFlag(flag + " expects " + expects + ", got '" + value + "'");
        start = comma + 1;
    }
    return {c[0], c[1], c[2]};
}

glm::vec3 parseColor(const std::string& flag, const std::string& value) {
    const glm::dvec3 c = parseTriple(flag, value, 0.0, 1e30, "R,G,B, three numbers in [0, 1e+30]");
    if (c.x == 0.0 && c.y == 0.0 && c.z == 0.0) badFlag(flag + " is black; leave out --env-color for no environment");
    return glm::vec3(c);
}

glm::vec3 parsePoint(const std::string& flag, const std::string& value) {
    const double big = double(std::numeric_limits<float>::max());
    return glm::vec3(parseTriple(flag, value, -big, big, "X,Y,Z, three finite numbers"));
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
    return out;
}

std::string alternatives(const std::vector<std::string>& names) {
    if (names.size() < 2) return joined(names, "");
    return joined(std::vector<std::string>(names.begin(), names.end() - 1), ", ") + " or " + names.back();
}

bool Parsed::has(const std::string& name) const {
    return std::find(given.begin(), given.end(), name) != given.end();
}

namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

bool isOption(const std::string& arg) { return !arg.empty() && arg[0] == '-'; }
bool isHelp(const std::string& arg) { return arg == "-h" || arg == "--help"; }
constexpr const char* kHelpTuning = "--help-tuning";

std::size_t findFlag(const std::vector<const FlagText*>& table, const std::string& arg) {
    for (std::size_t k = 0; k < table.size(); ++k)
        if (table[k]->names(arg)) return k;
    return kNone;
}

// `text` split into lines of at most `width` characters at spaces.
std::vector<std::string> wrapped(const std::string& text, std::size_t width) {
    std::vector<std::string> lines;
    std::string line;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find(' ', start);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(start, end - start);
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            lines.push_back(line);
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
        start = end + 1;
    }
    if (!line.empty()) lines.push_back(line);
    return lines;
}

// A flag's row: "  -o, --output FILE" padded to the help column, the help
// wrapped at 79 characters.
void addRow(std::string& out, const std::string& left, const std::string& help) {
    constexpr std::size_t kColumn = 26, kWidth = 79;
    out += left;
    const std::vector<std::string> lines = wrapped(help, kWidth - kColumn);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::size_t at = i == 0 && left.size() + 2 <= kColumn ? left.size() : 0;
        if (at == 0) out += "\n";
        out += std::string(kColumn - at, ' ') + lines[i];
    }
    out += "\n";
}

}  // namespace

bool hasTuning(const std::vector<const FlagText*>& table) {
    return std::any_of(table.begin(), table.end(), [](const FlagText* f) { return f->tuning; });
}

HelpPart helpRequested(const std::vector<const FlagText*>& table, const std::vector<std::string>& args) {
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (isHelp(args[i])) return HelpPart::Main;
        if (args[i] == kHelpTuning && hasTuning(table)) return HelpPart::Tuning;
        const std::size_t k = findFlag(table, args[i]);
        if (k != kNone && table[k]->takesValue()) ++i;
    }
    return HelpPart::None;
}

Parsed scanArgs(const std::string& command, const std::vector<const FlagText*>& table,
                const std::vector<std::string>& args, const Apply& apply) {
    Parsed parsed;
    struct Given {
        std::size_t flag;
        std::string given, value;
    };
    std::vector<Given> last;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (!isOption(a)) {
            parsed.positional.push_back(a);
            continue;
        }
        const std::size_t k = findFlag(table, a);
        if (k == kNone) badFlag("unknown option '" + a + "' (see 'strata " + command + " --help')");
        std::string value;
        if (table[k]->takesValue()) {
            if (i + 1 >= args.size()) badFlag(a + " needs a value");
            value = args[++i];
        }
        parsed.given.push_back(table[k]->name);
        if (table[k]->applyLast) last.push_back({k, a, value});
        else apply(k, a, value);
    }
    for (const Given& g : last) apply(g.flag, g.given, g.value);
    return parsed;
}

std::string formatHelp(const CommandText& command, const std::vector<const FlagText*>& table,
                       const std::vector<std::string>& defaults, HelpPart part) {
    const bool tuning = part == HelpPart::Tuning;
    const std::string summary =
        tuning ? joined(wrapped("The tuning flags of 'strata " + command.name + "', for measurements and tests: "
                                "each gives the same image, and the defaults suit the device.",
                                79),
                        "\n")
               : command.summary;
    std::string out = "usage: strata " + command.name + (command.usage.empty() ? "" : " " + command.usage) +
                      "\n\n" + summary + "\n\noptions:\n";
    for (std::size_t k = 0; k < table.size(); ++k) {
        const FlagText& f = *table[k];
        if (f.tuning != tuning) continue;
        const std::string value = f.takesValue() ? " " + f.metavar : "";
        const std::string def = defaults[k].empty() ? "" : " (default: " + defaults[k] + ")";
        addRow(out, "  " + (f.alias.empty() ? "" : f.alias + ", ") + f.name + value, f.help + def);
        if (!f.oldName.empty()) addRow(out, "  " + f.oldName + value, "(old name of " + f.name + ")");
    }
    if (tuning) return out;
    addRow(out, "  -h, --help", "print this help and do nothing else");
    if (!command.notes.empty()) out += "\n" + command.notes;
    if (hasTuning(table))
        out += "\nTuning flags, for measurements and tests: 'strata " + command.name + " " + kHelpTuning + "'.\n";
    return out;
}

}  // namespace strata::cli
