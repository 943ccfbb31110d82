#include "cli/man_page.h"

#include <CLI/CLI.hpp>
#include <ostream>
#include <vector>

namespace ssrt::cli {

namespace {

// `text` as roff running text: a backslash escaped, and a line that would start with a
// control character ('.' or '\'') or a space made plain text.
std::string roff(const std::string& text) {
    std::string out;
    bool lineStart = true;
    for (const char c : text) {
        if (lineStart && (c == '.' || c == '\'' || c == ' ')) out += "\\&";
        if (c == '\\') out += "\\e";
        else out += c;
        lineStart = c == '\n';
    }
    return out;
}

// An option name or a command line: '-' as the minus sign (\-), so that it can be copied
// from the rendered page and searched for.
std::string literal(const std::string& text) {
    std::string out;
    for (const char c : roff(text)) out += c == '-' ? std::string("\\-") : std::string(1, c);
    return out;
}

// "-s, --scene NAME" in roff: the spellings bold, the value's type italic.
std::string optionTerm(const CLI::Option& o) {
    std::string term;
    if (!o.nonpositional()) return "\\fI" + literal(o.get_name()) + "\\fR";
    for (const std::string& n : o.get_snames())
        term += (term.empty() ? "" : ", ") + ("\\fB" + literal("-" + n) + "\\fR");
    for (const std::string& n : o.get_lnames())
        term += (term.empty() ? "" : ", ") + ("\\fB" + literal("--" + n) + "\\fR");
    if (o.get_expected_max() != 0 && !o.get_type_name().empty())
        term += " \\fI" + literal(o.get_type_name()) + "\\fR";
    return term;
}

// "ssrt diff [OPTIONS] A B", as CLI11's help gives it.
std::string usage(const CLI::App& cmd) {
    std::string line = "ssrt " + cmd.get_name() + " [OPTIONS]";
    for (const CLI::Option* o : cmd.get_options()) {
        if (o->nonpositional()) continue;
        std::string name = o->get_name();
        if (o->get_expected_max() > 1) name += "...";
        line += " " + (o->get_required() ? name : "[" + name + "]");
    }
    return line;
}

void writeOption(const CLI::Option& o, std::ostream& out) {
    std::string help = o.get_description();
    if (!o.get_default_str().empty()) help += " (default: " + o.get_default_str() + ")";
    out << ".TP\n" << optionTerm(o) << "\n" << roff(help) << "\n";
}

// One command: its usage, description, positional arguments and options by help section, in
// the order `ssrt COMMAND --help` gives them (an option of the empty group is hidden there).
void writeManSection(const CLI::App& cmd, std::ostream& out) {
    out << ".SS \"" << literal(cmd.get_name()) << "\"\n"
        << ".B " << literal(usage(cmd)) << "\n.PP\n"
        << roff(cmd.get_description()) << "\n";
    for (const std::string& group : cmd.get_groups()) {
        if (group.empty()) continue;
        bool first = true;
        for (const CLI::Option* o : cmd.get_options()) {
            if (o->get_group() != group || !o->nonpositional()) continue;
            if (first) out << ".PP\n" << roff(group) << ":\n";
            first = false;
            writeOption(*o, out);
        }
    }
    bool first = true;
    for (const CLI::Option* o : cmd.get_options()) {
        if (o->nonpositional()) continue;
        if (first) out << ".PP\nArguments:\n";
        first = false;
        writeOption(*o, out);
    }
}

}  // namespace

CLI::App* addManCommand(CLI::App& app) {
    return app.add_subcommand(
        "man",
        "Print ssrt's manual page (roff, for man(1): ssrt man > ssrt.1; man -l ssrt.1), made "
        "from its own commands and flags; installed to share/man/man1/ssrt.1");
}

void writeManPage(const CLI::App& app, const std::string& exitStatus, const std::string& version,
                  std::ostream& out) {
    std::string description = app.get_description();
    if (description.rfind("ssrt: ", 0) == 0) description.erase(0, 6);
    const std::vector<const CLI::App*> commands =
        app.get_subcommands([](const CLI::App*) { return true; });
    // No date: the page is the same bytes for the same program.
    out << ".TH SSRT 1 \"\" \"" << roff(version) << "\" \"User Commands\"\n"
        << ".SH NAME\nssrt \\- " << roff(description) << "\n"
        << ".SH SYNOPSIS\n";
    for (const CLI::App* c : commands) out << ".B " << literal(usage(*c)) << "\n.br\n";
    out << ".B ssrt \\-\\-help\n.br\n.B ssrt \\-\\-version\n"
        << ".SH DESCRIPTION\n"
        << "ssrt is one program with a command per job; the first argument names the command, "
           "and the options after it are that command's.\n"
           ".B ssrt COMMAND \\-\\-help\n"
           "gives the same text as the section of this page for the command. Every option "
           "also takes its value after an equals sign (\\fB\\-\\-width=320\\fR).\n"
        << ".SH OPTIONS\n";
    for (const CLI::Option* o : app.get_options()) writeOption(*o, out);
    out << ".SH COMMANDS\n";
    for (const CLI::App* c : commands) writeManSection(*c, out);
    // The footer's text without its own heading ("Exit status: 0 success ...").
    std::string statuses = exitStatus;
    if (statuses.rfind("Exit status: ", 0) == 0) statuses.erase(0, 13);
    out << ".SH EXIT STATUS\n"
        << roff(statuses) << "\n"
        << ".SH ENVIRONMENT\n"
           ".TP\n.B SSRT_ISA\nThe kernels\n.B \\-\\-isa auto\nruns, when set.\n"
           ".TP\n.B SSRT_CACHE_DIR\nThe reference cache's folder (see FILES).\n"
        << ".SH FILES\n"
           ".TP\n.I $SSRT_CACHE_DIR\\fR, else \\fI$XDG_CACHE_HOME/ssrt\\fR, else "
           "\\fI~/.cache/ssrt\n"
           "The reference cache: the Embree references\n.B ssrt compare\nand\n.B ssrt reference\n"
           "render, kept for later runs.\n"
        << ".SH SEE ALSO\n"
           ".BR dot (1),\n.BR oiiotool (1)\n";
}

}  // namespace ssrt::cli
