// coif — command-line entry point. Nouns register themselves (tools/cli.h); this file only parses,
// dispatches and turns errors into messages and exit codes: 0 ok, 1 failure, 2 bad usage.
#include <exception>
#include <iostream>
#include <memory>
#include <sstream>

#include "models/core/error.h"
#include "online/gl_context.h"
#include "tools/assets.h"
#include "tools/cli.h"

namespace coif {
std::vector<std::byte> asset_bytes(std::string_view path) {
    const auto bytes = embedded::asset(path);
    if (!bytes) throw Error(std::string(path), "", "no such file compiled into coif");
    const auto* b = reinterpret_cast<const std::byte*>(bytes->data());
    return {b, b + bytes->size()};
}
}  // namespace coif

namespace {

// Lists each subcommand by the first line of its description; the whole text is shown by the
// subcommand's own --help.
class Formatter : public CLI::Formatter {
public:
    std::string make_subcommand(const CLI::App* sub) const override {
        std::stringstream out;
        const std::string& d = sub->get_description();
        CLI::detail::format_help(out, sub->get_display_name(true), d.substr(0, d.find('\n')), column_width_);
        return out.str();
    }
};

std::string version_text() {
    std::string text = "coif " COIF_VERSION "\n";
    try {
        auto context = coif::gl::Context::headless();
        text += "GL_RENDERER: " + context->renderer() + "\nGL_VERSION: " + context->version() +
                "\ncontext: " + context->platform() + "\n";
    } catch (const std::exception& e) {
        text += std::string("GL_RENDERER: unavailable (") + e.what() + ")\n";
    }
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "coif: a real-time hair renderer for weak GPUs. Hair is modelled as clusters (generalized disks cut into\n"
        "layered shells), its look is precomputed by a planar ray tracer into a database of 1D reflectance/alpha\n"
        "records (SATF), and it is lit by environment maps fitted as spherical Gaussian (SRBF) lights with a\n"
        "closed-form Marschner scattering model.\n\n"
        "Run `coif <command> --help` for each command. Images: .exr is linear, .png is tone-mapped sRGB.",
        "coif"};
    app.option_defaults()->always_capture_default();
    app.formatter(std::make_shared<Formatter>());
    app.set_version_flag("--version", [] { return version_text(); }, "Print the version and the OpenGL renderer, then exit");
    app.require_subcommand(1);
    app.footer(
        "\nExamples:\n"
        "  coif render -o hair.png                 render the embedded default scene (default style)\n"
        "  coif hair inspect model.hair            strand counts, lengths, bounding box\n"
        "  coif hair convert model.data model.hair convert a USC-HairSalon file to Yuksel's .hair\n\n"
        "Exit status: 0 success, 1 failure (message on stderr), 2 bad usage.");
    coif::cli::register_all(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return coif::cli::kExitUsage;
    } catch (const coif::Error& e) {
        std::cerr << "coif: error: " << e.what() << "\n";
        return coif::cli::kExitFailure;
    } catch (const std::exception& e) {
        std::cerr << "coif: error: " << e.what() << "\n";
        return coif::cli::kExitFailure;
    }
    return coif::cli::kExitOk;
}
