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


def test_interrupt_main_cancels_simulate():
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        stickslip.simulate("fig20", **LONG)
    elapsed = time.monotonic() - t0
    timer.join()
    assert elapsed < 2.0, elapsed


def test_interrupt_main_cancels_sweep():
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        stickslip.sweep("fig20", start=1e-4, stop=5e-3, steps=400, settle=500, samples=500)
    timer.join()
    assert time.monotonic() - t0 < 2.5


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
    assert len(during) >= 0.5 * (t1 - t0) / 0.01 * 0.5, (len(during), t1 - t0)
