#include "cli/reference_command.h"

#include <CLI/CLI.hpp>
#include <ostream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/interrupt.h"
#include "cli/options.h"
#include "cli/reference_cache.h"
#include "cli/sequence.h"
#include "cli/shard.h"
#include "core/tiles.h"
#include "io/image_io.h"

namespace ssrt::cli {

CLI::App* addReferenceCommand(CLI::App& app, ReferenceOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "reference",
        "Render the Embree reference image of a frame (the one 'ssrt compare' measures against) "
        "to an EXR of ref.* layers, and keep it in the reference cache; --shard renders a band "
        "of its rows for 'ssrt merge'");
    addSceneOptions(*cmd, o.render, truthDefaults());
    addTraceOptions(*cmd, o.render);
    addReferenceOptions(*cmd, o.truth);
    cmd->add_option("-o,--output", o.output,
                    "EXR to write: ref.color (exposed, as the frame's color), ref.direct, ref.ssr, "
                    "ref.ssgi, ref.specular, ref.diffuse (.R, .G, .B each)")
        ->type_name("FILE.exr")
        ->capture_default_str();
    addShardOption(*cmd, o.shard,
                   "rows: band K of N of the frame's tile rows; the band is rendered, not "
                   "cached, unless the cache already holds the whole reference");
    return cmd;
}

int runReference(const ReferenceOptions& o, std::ostream& /*out*/, std::ostream& err) {
    const InterruptScope interruptible;  // the reference stops between tiles (cli/interrupt.h)
    SceneRequest request = loadSceneRequest(o.render, truthDefaults());
    const RenderSettings& settings = request.settings;
    ReferenceSettings refSettings = referenceSettingsFrom(o.truth);
    refSettings.cancel = interruptFlag();
    if (!isExrPath(o.output))
        throw std::invalid_argument("-o: '" + o.output +
                                    "': a reference is written as an EXR (.exr): its planes are "
                                    "linear floats");
    std::string shardSource;
    const Shard shard = shardFrom(o.shard, &shardSource);
    std::optional<RowBand> band;
    if (shard.sharded()) {
        const int tileRows = (settings.height + kTileSize - 1) / kTileSize;
        if (shard.count > tileRows)
            throw std::invalid_argument("--shard: a " + std::to_string(settings.height) +
                                        "-row frame has " + plural(tileRows, "tile row") + " of " +
                                        std::to_string(kTileSize) + " pixels, so at most " +
                                        plural(tileRows, "shard") + " (asked for " +
                                        std::to_string(shard.count) + ")");
        band = referenceBand(settings.height, shard.index, shard.count);
    }
    const std::string output = shardFileName(o.output, shard);
    checkWritable(output);
    loadScene(request, err);
    const Scene& scene = request.scene;
    refSettings.maxDistance = marchLengths(settings.trace.march, scene.diagonal()).maxDistance;
    // Frame 0 of the request (its camera and frame index), as a single-frame compare has it.
    const FrameSequence sequence(request, SequencePlan{});
    const FrameInput input = sequence.input(0);
    std::ostream* progress = o.truth.quiet ? nullptr : &err;
    if (progress)
        *progress << "reference of " << request.name << " " << settings.width << "x"
                  << settings.height << " (" << describeReference(refSettings) << ", frame index "
                  << input.frameIndex << ")"
                  << (band ? ", " + describeShard(shard, shardSource) + ": rows " +
                                 std::to_string(band->y0) + " to " + std::to_string(band->y1 - 1)
                           : std::string())
                  << " on " << isaName(request.isa) << ", "
                  << plural(threadsFor(settings), "thread") << "...\n";

    const EmbreeScene embree(scene);
    const ReferenceSource source = referenceSourceFrom(o.truth, err);
    // The key hashes the whole scene: once, for the cache and for a band's header.
    const uint64_t key = referenceKey(scene, input.camera, input.frameIndex, settings, refSettings);
    bool fromCache = false;
    const auto stopped = [&] { return "0 of 1 reference (" + output + " not written)"; };
    stopIfInterrupted(stopped);
    const ReferenceImage ref = [&] {
        try {
            return referenceForKey(key, embree, scene, input, settings, refSettings, source,
                                   fromCache, band);
        } catch (const ReferenceCancelled&) {
            throw Interrupted(stopped());
        }
    }();
    if (progress) *progress << "reference: " << (fromCache ? "from the cache" : "rendered") << "\n";
    if (band) {
        writeReferenceImage(
            output, ref, band,
            {{kPartAttribute, kReferencePart},
             {kShardAttribute, shard.text()},
             {kRowsAttribute, std::to_string(band->y0) + " " + std::to_string(band->y1)},
             {kSizeAttribute,
              std::to_string(settings.width) + " " + std::to_string(settings.height)},
             {kKeyAttribute, referenceCacheFileName(key)}});
    } else {
        writeReferenceImage(output, ref);
    }
    if (progress) *progress << "wrote " << output << "\n";
    return kExitOk;
}

}  // namespace ssrt::cli
