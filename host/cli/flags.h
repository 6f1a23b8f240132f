// The command-line flags of strata as tables: each flag has a name, an
// optional short alias or former name, a value metavar (none for a switch),
// one line of help and how it sets the command's struct. The parser and the
// help text are both made from the same table, so they cannot disagree.
// Errors are strata::Error, one line: "strata: error: ...".
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace strata::cli {

[[noreturn]] void badFlag(const std::string& what);  // throws Error("strata: error: " + what)

// The value checks; `flag` is the flag as given, named in the error.
unsigned long parseUnsigned(const std::string& flag, const std::string& value, unsigned long min,
                            unsigned long max);
double parsePositive(const std::string& flag, const std::string& value, double max, const char* what);
double parseFinite(const std::string& flag, const std::string& value);
glm::vec3 parseColor(const std::string& flag, const std::string& value);  // R,G,B in [0, 1e30], not all 0
glm::vec3 parsePoint(const std::string& flag, const std::string& value);  // X,Y,Z, finite floats

// 16, 1000000000, 1e+30: integers as integers up to 1e15, the rest as %g.
std::string numberText(double v);
// {"a", "b", "c"}: "a, b or c".
std::string alternatives(const std::vector<std::string>& names);
std::string joined(const std::vector<std::string>& items, const std::string& separator);

// What a flag is, without the command it sets.
struct FlagText {
    std::string name;      // "--spp"
    std::string metavar;   // "N"; empty for a switch
    std::string help;      // one line: what it does, and its range
    std::string alias;     // a short form ("-o"), or empty
    std::string oldName;   // a former name still accepted ("--traversal"), or empty
    bool applyLast = false;  // applied after every other flag given, whatever the order
    bool tuning = false;     // a lab knob: listed by --help-tuning, not --help
    bool takesValue() const { return !metavar.empty(); }
    bool names(const std::string& arg) const {
        return arg == name || (!alias.empty() && arg == alias) || (!oldName.empty() && arg == oldName);
    }
};

template <class T>
struct Flag : FlagText {
    // Sets the command from the value (empty for a switch); `given` is the
    // flag as written, for errors.
    std::function<void(T& cmd, const std::string& given, const std::string& value)> set;
    // The default as text, read from the command's starting value; empty: none shown.
    std::function<std::string(const T& cmd)> show;

    Flag withAlias(std::string a) const { Flag f = *this; f.alias = std::move(a); return f; }
    Flag withOldName(std::string n) const { Flag f = *this; f.oldName = std::move(n); return f; }
    Flag withDefault(std::string text) const {
        Flag f = *this;
        f.show = [text](const T&) { return text; };
        return f;
    }
    Flag appliedLast() const { Flag f = *this; f.applyLast = true; return f; }
    Flag inTuning(bool on = true) const { Flag f = *this; f.tuning = on; return f; }
};

// What a command is, without its flags.
struct CommandText {
    std::string name;     // "render"
    std::string usage;    // after "strata NAME ": "SCENE.gltf|.glb [options]"
    std::string summary;  // one line, for `strata --help` and the command's own help
    std::string notes;    // lines after the flags, or empty
};

template <class T>
struct CommandSpec : CommandText {
    std::vector<Flag<T>> flags;
    T init;  // the command before any flag: the defaults the help shows
};

// What the parser found besides the flags it applied.
struct Parsed {
    std::vector<std::string> positional;
    std::vector<std::string> given;  // the flags given, by name (a former name as its flag's), in order
    bool has(const std::string& name) const;
};

using Apply = std::function<void(std::size_t flag, const std::string& given, const std::string& value)>;

// Walks `args`: a word starting with '-' must name a flag of `table` (the
// one after it is its value when it takes one), anything else is a
// positional argument. Calls `apply` for each flag in order, those marked
// applyLast after the rest.
Parsed scanArgs(const std::string& command, const std::vector<const FlagText*>& table,
                const std::vector<std::string>& args, const Apply& apply);
// Which help a command line asks for: none, the flags a user sets (-h,
// --help), or the lab knobs (--help-tuning, where the table has any).
enum class HelpPart { None, Main, Tuning };
bool hasTuning(const std::vector<const FlagText*>& table);
// The first help flag that stands where a flag may: help ignores the rest of the line.
HelpPart helpRequested(const std::vector<const FlagText*>& table, const std::vector<std::string>& args);
// "usage: strata NAME ...", the summary, every flag of `part` (the tuning
// flags or the others) with its metavar, help and default (defaults[i] for
// table[i], empty: none), then the notes; the main help ends with a line
// naming --help-tuning where the table has tuning flags.
std::string formatHelp(const CommandText& command, const std::vector<const FlagText*>& table,
                       const std::vector<std::string>& defaults, HelpPart part = HelpPart::Main);

template <class T>
std::vector<const FlagText*> flagTexts(const CommandSpec<T>& spec) {
    std::vector<const FlagText*> table;
    for (const Flag<T>& f : spec.flags) table.push_back(&f);
    return table;
}

template <class T>
Parsed parseFlags(const CommandSpec<T>& spec, const std::vector<std::string>& args, T& cmd) {
    return scanArgs(spec.name, flagTexts(spec), args,
                    [&](std::size_t k, const std::string& given, const std::string& value) {
                        spec.flags[k].set(cmd, given, value);
                    });
}

template <class T>
std::string helpText(const CommandSpec<T>& spec, HelpPart part = HelpPart::Main) {
    std::vector<std::string> defaults;
    for (const Flag<T>& f : spec.flags) defaults.push_back(f.show ? f.show(spec.init) : std::string());
    return formatHelp(spec, flagTexts(spec), defaults, part);
}

// Builders. `field` is a generic lambda giving the member a flag sets, for a
// command and for a const one: [](auto& c) -> auto& { return c.settings.spp; }.
template <class T>
Flag<T> flag(std::string name, std::string metavar, std::string help,
             std::function<void(T&, const std::string&, const std::string&)> set,
             std::function<std::string(const T&)> show = {}) {
    Flag<T> f;
    f.name = std::move(name);
    f.metavar = std::move(metavar);
    f.help = std::move(help);
    f.set = std::move(set);
    f.show = std::move(show);
    return f;
}

// A switch: `on` runs when it is given.
template <class T>
Flag<T> toggle(std::string name, std::string help, std::function<void(T&)> on) {
    return flag<T>(std::move(name), "", std::move(help),
                   [on](T& c, const std::string&, const std::string&) { on(c); });
}

// A string (a file name) stored as given; the default shown is the starting value, if any.
template <class T, class Field>
Flag<T> text(std::string name, std::string metavar, std::string help, Field field) {
    return flag<T>(
        std::move(name), std::move(metavar), std::move(help),
        [field](T& c, const std::string&, const std::string& v) { field(c) = v; },
        [field](const T& c) { return std::string(field(c)); });
}

// An integer in [min, max].
template <class T, class Field>
Flag<T> integer(std::string name, std::string metavar, std::string help, unsigned long min, unsigned long max,
                Field field) {
    return flag<T>(
        std::move(name), std::move(metavar),
        help + ", in [" + std::to_string(min) + ", " + std::to_string(max) + "]",
        [=](T& c, const std::string& given, const std::string& v) {
            auto& member = field(c);
            member = static_cast<std::remove_reference_t<decltype(member)>>(parseUnsigned(given, v, min, max));
        },
        [field](const T& c) { return std::to_string(field(c)); });
}

// A number in (0, max]; `what` names it in the error ("seconds").
template <class T, class Field>
Flag<T> positive(std::string name, std::string metavar, std::string help, double max, const char* what,
                 Field field) {
    return flag<T>(
        std::move(name), std::move(metavar), help + ", in (0, " + numberText(max) + "]",
        [=](T& c, const std::string& given, const std::string& v) {
            auto& member = field(c);
            member = static_cast<std::remove_reference_t<decltype(member)>>(parsePositive(given, v, max, what));
        },
        [field](const T& c) { return numberText(field(c)); });
}

// Any finite number.
template <class T, class Field>
Flag<T> finite(std::string name, std::string metavar, std::string help, Field field) {
    return flag<T>(
        std::move(name), std::move(metavar), std::move(help),
        [field](T& c, const std::string& given, const std::string& v) { field(c) = parseFinite(given, v); },
        [field](const T& c) { return numberText(field(c)); });
}

// One of a list of names, each standing for a value; the metavar is the
// names joined by '|'.
template <class V>
using Choices = std::vector<std::pair<std::string, V>>;

template <class T, class V, class Field>
Flag<T> choice(std::string name, std::string help, Choices<V> choices, Field field) {
    std::vector<std::string> names;
    for (const auto& c : choices) names.push_back(c.first);
    return flag<T>(
        std::move(name), joined(names, "|"), std::move(help),
        [=](T& c, const std::string& given, const std::string& v) {
            for (const auto& [key, value] : choices)
                if (key == v) {
                    field(c) = value;
                    return;
                }
            badFlag(given + " expects " + alternatives(names) + ", got '" + v + "'");
        },
        [=](const T& c) {
            for (const auto& [key, value] : choices)
                if (value == field(c)) return key;
            return std::string();
        });
}

}  // namespace strata::cli
