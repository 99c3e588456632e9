"""Runs release the GIL, and Ctrl-C (SIGINT / KeyboardInterrupt) cancels them within a second."""
import _thread
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

import stickslip

LONG = dict(cycles=200000, output_every=0.05)  # minutes if it were not cancelled


def interrupt_later(delay=0.5):
    """Raises KeyboardInterrupt in the main thread after `delay` s; returns a list that gets the time it did."""
    when = []

    def fire():
        when.append(time.monotonic())
        _thread.interrupt_main()

    timer = threading.Timer(delay, fire)
    timer.start()
    return timer, when


def test_interrupt_main_cancels_simulate():
    timer, when = interrupt_later()
    with pytest.raises(KeyboardInterrupt):
        stickslip.simulate("fig20", **LONG)
    done = time.monotonic()
    timer.join()
    assert done - when[0] < 2.0, done - when[0]


def test_interrupt_main_cancels_sweep():
    timer, when = interrupt_later()
    with pytest.raises(KeyboardInterrupt):
        stickslip.sweep("fig20", start=1e-4, stop=5e-3, steps=400, settle=500, samples=500)
    done = time.monotonic()
    timer.join()
    assert done - when[0] < 2.0, done - when[0]


def test_interrupt_main_cancels_identify(damper):
    data = [str(p) for p in sorted(damper.glob("*.csv"))]
    timer, when = interrupt_later(1.0)
    with pytest.raises(KeyboardInterrupt):
        stickslip.identify(data, setup="prescribed")  # about half a minute if not cancelled
    done = time.monotonic()
    timer.join()
    assert done - when[0] < 2.0, done - when[0]


def test_sigint_cancels_a_run_in_a_subprocess():
    code = ("import stickslip, sys\n"
            "print('started', flush=True)\n"
            "try:\n"
            "    stickslip.simulate('fig20', cycles=200000, output_every=0.05)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True); sys.exit(7)\n")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True, env=os.environ.copy())
    assert p.stdout.readline().strip() == "started"
    time.sleep(0.5)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        rc = p.wait(timeout=5)
    finally:
        if p.poll() is None:
            p.kill()
    assert time.monotonic() - t0 < 2.0
    assert rc == 7 and p.stdout.read().strip() == "interrupted"


def test_gil_is_released_during_a_run():
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    th = threading.Thread(target=count)
    th.start()
    t0 = time.monotonic()
    stickslip.simulate("fig20", cycles=1500, output_every=0.01)
    t1 = time.monotonic()
    stop.set()
    th.join()
    during = [t for t in ticks if t0 < t < t1]
    assert t1 - t0 > 0.2, "run too short to tell"
    # With the GIL held for the whole run the counter could not tick at all (0 or 1 ticks).
    assert len(during) >= 5, (len(during), t1 - t0)
