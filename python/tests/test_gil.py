"""Rendering releases the GIL: Python threads run while a frame renders, and two renders run
at once (each with its own history) giving the bits one alone gives."""

import sys
import threading
import time

import numpy as np

import ssrt


def test_python_runs_while_a_frame_renders():
    renderer = ssrt.Renderer(ssrt.RenderSettings(width=320, height=180, threads=1))
    scene = ssrt.Scene("spheres")
    ticks = [0]
    done = threading.Event()

    def count():  # sleeps between ticks, so it needs the GIL back after each one
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.0002)

    # The main thread then gives the GIL up only when it blocks or a call releases it.
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    counter = threading.Thread(target=count)
    try:
        counter.start()
        before = ticks[0]
        renderer.render(scene)
        during = ticks[0] - before
    finally:
        done.set()
        counter.join()
        sys.setswitchinterval(interval)
    # Holding the GIL, the counter could not tick once during the call.
    assert during > 5


def test_two_threads_render_the_same_bits():
    renderer = ssrt.Renderer(ssrt.RenderSettings(width=96, height=54))
    scene = ssrt.Scene("cornell")
    alone = renderer.render(scene, ssrt.FrameInput.still(scene, 2), ssrt.History())
    results = [None, None]

    def work(i):
        history = ssrt.History()
        for index in range(3):
            results[i] = renderer.render(scene, ssrt.FrameInput.still(scene, index), history)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results[0] is not None and results[1] is not None
    for name in ("color.R", "viewZ", "ssgi.G"):
        assert np.array_equal(results[0][name], results[1][name]), name
    # Frame 2 after two frames of history differs from frame 2 alone only through the history.
    assert np.array_equal(results[0]["viewZ"], alone["viewZ"])
