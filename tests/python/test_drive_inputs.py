"""The drive train's run-time inputs from Python (the ones SimTwo scripts reach through
SetAxisSpring, SetFrictionDef, SetMotorControllerPars and GetAxisEnergy), on the spinner scene of
tests/plugins/pascal_script/script_api_drive: a rotor of I = 0.0141667 kg m^2 on a vertical
hinge."""

import math
import os

import pytest

import s2sim

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
SPINNER = os.path.join(SOURCE, "tests", "plugins", "pascal_script", "script_api_drive")
AXIS = "robots/spinner/axes/spin/"
INERTIA = (0.4 ** 2 + 0.1 ** 2) / 12


def test_a_spring_set_as_an_input_swings_at_sqrt_k_over_i():
    sim = s2sim.Simulation(SPINNER)
    sim.set_input(AXIS + "motor_active", 0)
    sim.set_input(AXIS + "spring_k", 2.0)
    sim.set_input(AXIS + "spring_zeropos", 0.3)
    crossings, previous = [], None
    while sim.time < 3.0:
        sim.step()
        q = sim.signal(AXIS + "pos") - 0.3
        if previous is not None and previous < 0 <= q:
            crossings.append(sim.time - sim.tick_s * q / (q - previous))
        previous = q
    period = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert period == pytest.approx(2 * math.pi * math.sqrt(INERTIA / 2.0), rel=1e-4)


def test_the_energy_meter_counts_only_what_the_supply_gives():
    sim = s2sim.Simulation(SPINNER)
    drawn = given_back = 0.0
    sim.set_input(AXIS + "ref_voltage", 12)
    while sim.time < 1.0:
        if sim.time >= 0.5:
            sim.set_input(AXIS + "ref_voltage", 0.3)  # slower than the rotor: it drives back
        sim.step()
        p = sim.signal(AXIS + "power") * sim.tick_s
        if p > 0:
            drawn += p
        else:
            given_back += p
    assert given_back < -0.02
    assert sim.signal(AXIS + "energy_drawn") == pytest.approx(drawn, abs=1e-12)
    assert sim.signal(AXIS + "energy") == pytest.approx(drawn + given_back, abs=1e-12)
