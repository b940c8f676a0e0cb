"""s2sim.envs: the environments as plain classes (gymnasium is not a Debian package here), and
as gymnasium.Env subclasses registered under s2sim/ ids, shown with a stand-in gymnasium module
in a subprocess."""

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import s2sim
from s2sim import envs

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
NXT = os.path.join(SOURCE, "scenes", "nxt")
RIGHT, LEFT = "robots/nxt/axes/right/ref_voltage", "robots/nxt/axes/left/ref_voltage"


def test_cart_pole_episodes_repeat_per_seed_and_end_when_the_pole_falls():
    env = envs.CartPoleEnv()  # its scene travels with the package
    obs, info = env.reset(seed=3)
    assert obs.shape == (4,) and env.observation_space.contains(obs)
    assert -2.0 <= info["push_N"] <= 2.0
    first = [env.step([10.0]) for _ in range(60)]
    again, info_again = env.reset(seed=3)
    assert np.array_equal(again, obs) and info_again == info
    for step in first:
        assert np.array_equal(env.step([10.0])[0], step[0])
    assert any(s[2] for s in first), "pushed hard for 1.2 s, the pole falls"
    fallen = next(s for s in first if s[2])
    assert fallen[1] == 0.0 and first[0][1] == 1.0
    other, _ = env.reset(seed=4)
    assert not np.array_equal(other, obs)
    sample = env.action_space.sample()
    assert env.action_space.contains(sample) and sample.shape == (1,)


def test_a_scene_environment_observes_signals_and_acts_through_inputs():
    env = envs.SimulationEnv(NXT, observations=["robots/nxt/x", "robots/nxt/axes/*/speed"],
                             actions=[RIGHT, LEFT], action_low=-9.0, action_high=9.0,
                             max_steps=5, reward=lambda e, obs, a: obs[0],
                             terminated=lambda e, obs: obs[0] > 1.0)
    assert env.observation_names[0] == "robots/nxt/x" and len(env.observation_names) == 3
    obs, info = env.reset(seed=1)
    assert info["time"] == 0.0 and obs.shape == (3,)
    for i in range(5):
        obs, reward, terminated, truncated, info = env.step([20.0, -20.0])  # clipped to 9 V
        assert truncated == (i == 4) and not terminated
    assert env.sim.input(RIGHT) == 9.0 and env.sim.input(LEFT) == -9.0
    assert reward == obs[0] > 0
    assert info["time"] == pytest.approx(5 * env.sim.control_period)
    with pytest.raises(s2sim.UsageError, match="2 values"):
        env.step([1.0])
    with pytest.raises(s2sim.UsageError, match="robots/nxt/axes/rigth"):
        envs.SimulationEnv(NXT, "robots/nxt/x", ["robots/nxt/axes/rigth/ref_voltage"], -1, 1)
    with pytest.raises(s2sim.UsageError, match="robots/nxt/nope"):
        envs.SimulationEnv(NXT, "robots/nxt/nope", [RIGHT], -1, 1)
    with pytest.raises(s2sim.UsageError, match="must not exceed"):
        envs.SimulationEnv(NXT, "robots/nxt/x", [RIGHT], 1, -1)


def test_without_gymnasium_nothing_is_registered():
    if envs.gymnasium is not None:
        pytest.skip("gymnasium is installed: the registration is the real one")
    assert envs.register_envs() == []
    assert envs.SimulationEnv.__bases__ == (object,)


FAKE_GYMNASIUM = '''
registry = {}

class Env:
    np_random = None
    def reset(self, *, seed=None, options=None):
        import numpy as np
        if seed is not None or self.np_random is None:
            self.np_random = np.random.default_rng(seed)

def register(id, entry_point, **kwargs):
    registry[id] = entry_point

def make(id, **kwargs):
    import importlib
    module, name = registry[id].split(":")
    return getattr(importlib.import_module(module), name)(**kwargs)
'''

FAKE_SPACES = '''
import numpy as np

class Box:
    def __init__(self, low, high, dtype=np.float32):
        self.low, self.high, self.dtype = np.asarray(low), np.asarray(high), dtype
        self.shape = self.low.shape
        self.np_random = np.random.default_rng()
    def seed(self, seed=None):
        self.np_random = np.random.default_rng(seed)
    def sample(self):
        return self.np_random.uniform(self.low, self.high)
    def contains(self, x):
        return np.shape(x) == self.shape
'''


def test_with_gymnasium_the_environments_are_envs_registered_under_s2sim_ids(tmp_path):
    fake = tmp_path / "gymnasium"
    fake.mkdir()
    (fake / "__init__.py").write_text(FAKE_GYMNASIUM)
    (fake / "spaces.py").write_text(FAKE_SPACES)
    code = textwrap.dedent('''
        import gymnasium
        import s2sim.envs as envs
        assert issubclass(envs.CartPoleEnv, gymnasium.Env)
        assert sorted(gymnasium.registry) == ["s2sim/CartPole-v0", "s2sim/Scene-v0"]
        env = gymnasium.make("s2sim/CartPole-v0")
        assert type(env.action_space).__module__ == "gymnasium.spaces"
        obs, info = env.reset(seed=3)
        obs2, info2 = env.reset(seed=3)
        assert (obs == obs2).all() and info == info2
        print(env.step([1.0])[1])
    ''')
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), env.get("PYTHONPATH", "")])
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "1.0"
