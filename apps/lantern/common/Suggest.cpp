// The nearest valid name for a mistyped subcommand or option: walks the arguments through the
// CLI11 definition as the parser does, stops at the first name it does not know and looks for
// the nearest one it does.
#include "common/Suggest.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

namespace lantern::cli {
namespace {

// Options renamed so that every subcommand uses the same names (docs/cli.md).
const std::map<std::string, std::string>& renamedOptions() {
    static const std::map<std::string, std::string> renamed = {
        {"--resolutions", "--width W1,W2,... --height H1,H2,..."},
        {"--sizes", "--width W1,W2,... --height H1,H2,..."},
    };
    return renamed;
}

std::vector<std::string> optionNames(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::Option* opt : app.get_options()) {
        for (const std::string& l : opt->get_lnames())
            names.push_back("--" + l);
        for (const std::string& s : opt->get_snames())
            names.push_back("-" + s);
    }
    return names;
}

std::string unknownOption(const CLI::App& app, const std::string& name) {
    std::string text = "`" + commandPath(app) + "` has no option " + name;
    if (const auto renamed = renamedOptions().find(name); renamed != renamedOptions().end())
        return text + "; it is now " + renamed->second;
    if (auto near = nearestName(name, optionNames(app))) return text + "; did you mean " + *near + "?";
    return text + " (`" + commandPath(app) + " --help` lists them)";
}

std::string unknownSubcommand(const CLI::App& app, const std::string& word) {
    std::vector<std::string> names;
    for (const CLI::App* sub : subcommandsOf(app))
        names.push_back(sub->get_name());
    std::string text = "`" + commandPath(app) + "` has no subcommand \"" + word + "\"";
    if (auto near = nearestName(word, names)) return text + "; did you mean `" + *near + "`?";
    std::string all;
    for (const std::string& n : names)
        all += (all.empty() ? "" : ", ") + n;
    return text + " (" + all + ")";
}

bool looksLikeOption(const std::string& arg) {
    if (arg.size() < 2 || arg[0] != '-') return false;
    // A negative number is a value, not an option.
    return !(std::isdigit(static_cast<unsigned char>(arg[1])) || arg[1] == '.');
}

} // namespace

std::vector<const CLI::App*> subcommandsOf(const CLI::App& app) {
    return app.get_subcommands([](const CLI::App*) { return true; });
}

std::string commandPath(const CLI::App& app) {
    std::string path;
    for (const CLI::App* a = &app; a; a = a->get_parent())
        path = a->get_name() + (path.empty() ? "" : " " + path);
    return path;
}

std::size_t editDistance(std::string_view a, std::string_view b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
    for (std::size_t i = 0; i <= n; ++i)
        d[i][0] = i;
    for (std::size_t j = 0; j <= m; ++j)
        d[0][j] = j;
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[n][m];
}

std::optional<std::string> nearestName(std::string_view typed,
                                       const std::vector<std::string>& names) {
    std::optional<std::string> best;
    std::size_t bestDistance = std::max<std::size_t>(2, typed.size() / 3) + 1;
    for (const std::string& name : names) {
        const std::size_t d = editDistance(typed, name);
        if (d < bestDistance) {
            bestDistance = d;
            best = name;
        }
    }
    if (best) return best;
    // An abbreviation: the start of exactly one name.
    std::vector<std::string> starts;
    for (const std::string& name : names)
        if (typed.size() >= 3 && name.rfind(typed, 0) == 0) starts.push_back(name);
    if (starts.size() == 1) return starts.front();
    return std::nullopt;
}

std::optional<std::string> diagnoseUnknownName(const CLI::App& root,
                                               const std::vector<std::string>& args) {
    const CLI::App* app = &root;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--") break;
        if (looksLikeOption(arg)) {
            const std::string name = arg.rfind("--", 0) == 0 ? arg.substr(0, arg.find('='))
                                                             : arg.substr(0, 2);
            const CLI::Option* opt = app->get_option_no_throw(name);
            if (!opt) {
                if (app->get_allow_extras()) continue; // passed on (farm submit -> render)
                return unknownOption(*app, name);
            }
            // An option with a value takes the next word, unless it came attached.
            const bool attached = arg.find('=') != std::string::npos ||
                                  (arg.rfind("--", 0) != 0 && arg.size() > 2);
            if (opt->get_items_expected_max() > 0 && !attached) ++i;
            continue;
        }
        const auto subs = subcommandsOf(*app);
        const auto sub = std::find_if(subs.begin(), subs.end(),
                                      [&](const CLI::App* s) { return s->check_name(arg); });
        if (sub != subs.end()) {
            app = *sub;
            continue;
        }
        // A word where a subcommand must come: the app requires one and takes no positionals.
        const bool positionals = !app->get_options([](const CLI::Option* o) {
                                         return o->get_positional();
                                     }).empty();
        if (!subs.empty() && !positionals) return unknownSubcommand(*app, arg);
    }
    return std::nullopt;
}

std::optional<std::string> diagnoseSwallowedOption(const CLI::App& root) {
    for (const CLI::App* app = &root; app;) {
        std::set<std::string> names;
        for (const CLI::Option* o : app->get_options()) {
            for (const std::string& l : o->get_lnames()) names.insert("--" + l);
            for (const std::string& s : o->get_snames()) names.insert("-" + s);
        }
        for (const CLI::Option* o : app->get_options()) {
            if (o->get_positional() || o->get_items_expected_max() == 0) continue;
            for (const std::string& value : o->results())
                if (names.count(value))
                    return o->get_name() + ": its value is the option " + value +
                           "; give " + o->get_name() + " a value, or leave it out";
        }
        const auto parsed = app->get_subcommands();
        app = parsed.empty() ? nullptr : parsed.front();
    }
    return std::nullopt;
}

} // namespace lantern::cli
