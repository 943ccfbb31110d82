"""Embedding in a threaded Python tool: 8 threads, each with its own Renderer, scene and
sequence, rendering at once (the GIL released while they render), give the bits each gives
alone; a History one thread's render is using is refused to another with a RuntimeError."""

import threading

import ssrt
from conftest import plane_hash

SCENES = ["cornell", "spheres", "thin", "corridor", "offscreen", "occluded", "bunny", "fence"]


def sequence_hashes(scene, threads):
    """Every plane of every frame of a short sequence with one history, by frame and name."""
    renderer = ssrt.Renderer(ssrt.RenderSettings(width=160, height=90, threads=threads))
    return [{name: plane_hash(frame[name]) for name in frame.layers}
            for frame in renderer.sequence(ssrt.Scene(scene), 3, warmup_frames=1)]


def test_eight_threads_render_the_bits_each_renders_alone():
    jobs = [(scene, i % 3) for i, scene in enumerate(SCENES)]  # threads 0 (all), 1, 2
    alone = [sequence_hashes(*job) for job in jobs]
    together = [None] * len(jobs)
    start = threading.Barrier(len(jobs))

    def work(i):
        start.wait()  # all at once
        together[i] = sequence_hashes(*jobs[i])

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(jobs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for job, a, b in zip(jobs, alone, together):
        assert b == a, job


def test_a_history_in_use_is_refused_to_another_thread():
    scene = ssrt.Scene("cornell")
    history = ssrt.History()
    # Long enough that the other thread tries while it runs (it waits until it does).
    slow = ssrt.Renderer(ssrt.RenderSettings(width=640, height=360, threads=1))
    done = threading.Event()
    first = threading.Thread(target=lambda: (slow.render(scene, None, history), done.set()))
    first.start()
    while not history.in_use and not done.is_set():
        pass
    refused = None
    try:
        ssrt.Renderer(ssrt.RenderSettings(width=96, height=54)).render(scene, None, history)
    except RuntimeError as e:
        refused = str(e)
    first.join()
    assert refused == ("render: the FrameHistory is in use by another render call "
                       "(a history carries one sequence, one frame at a time)")
    assert not history.in_use
    # Let go when that call returned: the sequence goes on.
    ssrt.Renderer(ssrt.RenderSettings(width=96, height=54)).render(scene, None, history)
