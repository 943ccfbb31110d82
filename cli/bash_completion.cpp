#include "cli/bash_completion.h"

#include <CLI/CLI.hpp>
#include <ostream>
#include <vector>

#include "scenes/scene_names.h"

namespace ssrt::cli {

namespace {

// The shells `ssrt completion` writes a script for.
const std::vector<std::string> kShells = {"bash"};

std::string spaced(const std::vector<std::string>& words) {
    std::string out;
    for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
    return out;
}

// Every spelling of one option: "-s --scene".
std::vector<std::string> spellings(const CLI::Option& o) {
    std::vector<std::string> names;
    for (const std::string& n : o.get_snames()) names.push_back("-" + n);
    for (const std::string& n : o.get_lnames()) names.push_back("--" + n);
    return names;
}

// What the word after an option completes to.
enum class ValueKind { None, Flag, Scene, File };

ValueKind valueKind(const CLI::Option& o) {
    if (o.get_expected_max() == 0) return ValueKind::Flag;  // a flag: no value
    for (const std::string& n : o.get_lnames())
        if (n == "scene") return ValueKind::Scene;
    // "FILE", "FILE.png", "DIR": a path.
    const std::string type = o.get_type_name();
    if (type.rfind("FILE", 0) == 0 || type.rfind("DIR", 0) == 0) return ValueKind::File;
    return ValueKind::None;
}

// The case arm of one command: completes the value of its options that take one, and
// otherwise its flags (a word starting with '-') or its positional arguments.
void writeCompletionArm(const CLI::App& cmd, std::ostream& out) {
    std::vector<std::string> flags, scene, file, other;
    bool positionals = false;
    for (const CLI::Option* o : cmd.get_options()) {
        if (!o->nonpositional()) {
            positionals = true;
            continue;
        }
        const std::vector<std::string> names = spellings(*o);
        flags.insert(flags.end(), names.begin(), names.end());
        switch (valueKind(*o)) {
            case ValueKind::Flag: break;
            case ValueKind::Scene: scene.insert(scene.end(), names.begin(), names.end()); break;
            case ValueKind::File: file.insert(file.end(), names.begin(), names.end()); break;
            case ValueKind::None: other.insert(other.end(), names.begin(), names.end()); break;
        }
    }
    const auto pattern = [](std::vector<std::string> names) {
        std::string out;
        for (const std::string& n : names) out += (out.empty() ? "" : "|") + n;
        return out;
    };
    out << "        " << cmd.get_name() << ")\n";
    if (!scene.empty() || !file.empty() || !other.empty()) out << "            case \"$prev\" in\n";
    if (!scene.empty())
        out << "                " << pattern(scene)
            << ") _ssrt_words \"$scenes\"; _ssrt_files '!*.[gG][lL][tTbB]*'; return ;;\n";
    if (!file.empty()) out << "                " << pattern(file) << ") _ssrt_files; return ;;\n";
    if (!other.empty()) out << "                " << pattern(other) << ") return ;;\n";
    if (!scene.empty() || !file.empty() || !other.empty()) out << "            esac\n";
    out << "            flags=\"" << spaced(flags) << "\"\n";
    if (cmd.get_name() == "completion")
        out << "            positional=(words \"" << spaced(kShells) << "\")\n";
    else if (positionals) out << "            positional=(files)\n";
    out << "            ;;\n";
}

}  // namespace

CLI::App* addCompletionCommand(CLI::App& app, std::string& shell) {
    CLI::App* cmd = app.add_subcommand(
        "completion",
        "Print a shell completion script for ssrt, made from its own commands and flags (load "
        "it with: source <(ssrt completion bash); installed to "
        "share/bash-completion/completions/ssrt)");
    cmd->add_option("SHELL", shell, "The shell: " + spaced(kShells))
        ->required()
        ->check(CLI::IsMember(kShells));
    return cmd;
}

void writeBashCompletion(const CLI::App& app, std::ostream& out) {
    std::vector<std::string> commands;
    for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
        commands.push_back(c->get_name());
    std::vector<std::string> topFlags;
    for (const CLI::Option* o : app.get_options()) {
        const std::vector<std::string> names = spellings(*o);
        topFlags.insert(topFlags.end(), names.begin(), names.end());
    }
    out << "# bash completion for ssrt, written by 'ssrt completion bash' from ssrt's own\n"
           "# commands and flags. Load it with: source <(ssrt completion bash)\n\n"
           "_ssrt_words() {\n"
           "    local w\n"
           "    while IFS= read -r w; do COMPREPLY+=(\"$w\"); done < <(compgen -W \"$1\" -- "
           "\"$cur\")\n"
           "}\n\n"
           "# Files, or with a pattern the files -X keeps (compgen -X drops what matches) and\n"
           "# every folder, to go on into.\n"
           "_ssrt_files() {\n"
           "    local w\n"
           "    while IFS= read -r w; do COMPREPLY+=(\"$w\"); done < <(compgen -f ${1:+-X \"$1\"} "
           "-- \"$cur\")\n"
           "    if [ -n \"${1:-}\" ]; then\n"
           "        while IFS= read -r w; do COMPREPLY+=(\"$w\"); done < <(compgen -d -- "
           "\"$cur\")\n"
           "    fi\n"
           "    compopt -o filenames 2>/dev/null || true\n"
           "}\n\n"
           "_ssrt() {\n"
           "    COMPREPLY=()\n"
           "    local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"\" command=\"\" flags=\"\" i\n"
           "    local -a positional=()\n"
           "    [ \"$COMP_CWORD\" -gt 0 ] && prev=\"${COMP_WORDS[COMP_CWORD - 1]}\"\n"
           "    # --scene=cor: bash splits the word at '='.\n"
           "    if [ \"$cur\" = \"=\" ]; then prev=\"${COMP_WORDS[COMP_CWORD - 1]}\"; cur=\"\"; "
           "fi\n"
           "    if [ \"$prev\" = \"=\" ] && [ \"$COMP_CWORD\" -gt 1 ]; then\n"
           "        prev=\"${COMP_WORDS[COMP_CWORD - 2]}\"\n"
           "    fi\n"
           "    local scenes=\""
        << spaced(knownSceneNames())
        << "\"\n"
           "    for ((i = 1; i < COMP_CWORD; i++)); do\n"
           "        case \"${COMP_WORDS[i]}\" in\n"
           "            -*) ;;\n"
           "            *) command=\"${COMP_WORDS[i]}\"; break ;;\n"
           "        esac\n"
           "    done\n"
           "    case \"$command\" in\n"
           "        \"\")\n"
           "            flags=\""
        << spaced(topFlags)
        << "\"\n"
           "            positional=(words \""
        << spaced(commands)
        << "\")\n"
           "            ;;\n";
    for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
        writeCompletionArm(*c, out);
    out << "        *) return ;;\n"
           "    esac\n"
           "    if [[ \"$cur\" == -* ]]; then\n"
           "        _ssrt_words \"$flags\"\n"
           "    elif [ \"${positional[0]:-}\" = words ]; then\n"
           "        _ssrt_words \"${positional[1]}\"\n"
           "    elif [ \"${positional[0]:-}\" = files ]; then\n"
           "        _ssrt_files\n"
           "    fi\n"
           "}\n"
           "complete -F _ssrt ssrt\n";
}

}  // namespace ssrt::cli
