"""Reinforcement-learning environments over S2Sim scenes (docs/python.md, "Environments").

``SimulationEnv`` observes signals and acts through inputs on any scene; ``CartPoleEnv`` is the
cart-pole balancing task of scenes/cartpole. With gymnasium installed they are
``gymnasium.Env`` subclasses with ``gymnasium.spaces.Box`` spaces, registered as
``s2sim/Scene-v0`` and ``s2sim/CartPole-v0`` (``gymnasium.make("s2sim/CartPole-v0")`` after
``import s2sim.envs``, or after a pip install through gymnasium's plugin entry point). Without
gymnasium they are plain classes with the same interface: ``reset(seed=None, options=None)
-> (observation, info)``, ``step(action) -> (observation, reward, terminated, truncated,
info)``, ``action_space`` and ``observation_space`` with ``low``, ``high``, ``shape``,
``sample()`` and ``contains()``.
"""

import os

import numpy as np

try:
    import gymnasium
    from gymnasium import spaces as _spaces
except ImportError:  # the plain classes below
    gymnasium = None
    _spaces = None

from ._s2sim import Simulation, UsageError

_Base = gymnasium.Env if gymnasium is not None else object

# The scenes of the registered environments, shipped in the package (python/CMakeLists.txt).
PACKAGE_SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes")


class Box:
    """gymnasium.spaces.Box's essentials, when gymnasium is not installed."""

    def __init__(self, low, high, dtype=np.float64, seed=None):
        self.low = np.asarray(low, dtype=dtype)
        self.high = np.asarray(high, dtype=dtype)
        self.shape = self.low.shape
        self.dtype = np.dtype(dtype)
        self.np_random = np.random.default_rng(seed)

    def seed(self, seed=None):
        self.np_random = np.random.default_rng(seed)

    def sample(self):
        low = np.where(np.isfinite(self.low), self.low, -1.0)
        high = np.where(np.isfinite(self.high), self.high, 1.0)
        return self.np_random.uniform(low, high).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x)
        return x.shape == self.shape and bool(np.all(x >= self.low) and np.all(x <= self.high))


def _box(low, high):
    if _spaces is not None:
        return _spaces.Box(np.asarray(low, dtype=np.float64), np.asarray(high, dtype=np.float64),
                           dtype=np.float64)
    return Box(low, high)


def _listed(patterns, what):
    if isinstance(patterns, str):
        return [patterns]
    patterns = list(patterns)
    if not patterns or not all(isinstance(p, str) for p in patterns):
        raise UsageError(f"{what} must be a signal or input name (or glob), or a non-empty list "
                         f"of them, got {patterns!r}")
    return patterns


class SimulationEnv(_Base):
    """An environment over a scene: the observation is the signals ``observations`` matches (a
    name, a glob or a list of them, in order), the action sets the inputs ``actions`` names (in
    order) within ``[action_low, action_high]`` (clipped), and each step advances
    ``control_period`` seconds (default: the scene's). ``reward(env, observation, action)`` and
    ``terminated(env, observation)`` are the task (default: reward 0, never terminated);
    ``max_steps`` truncates an episode. ``reset(seed=s)`` reseeds the simulation's random
    streams (sensor noise: the same seed gives the same episode) and ``self.np_random``.
    Other keyword arguments go to ``s2sim.Simulation``.
    """

    metadata = {"render_modes": []}

    def __init__(self, scene, observations, actions, action_low, action_high,
                 control_period=None, max_steps=None, reward=None, terminated=None, **simulation):
        self.sim = Simulation(scene, **simulation)
        observed = _listed(observations, "observations")
        acted = _listed(actions, "actions")
        ids = self.sim.signal_ids
        # Indices into the zero-copy signal view: an observation is one gather, no name look-up.
        self.observation_names = [name for p in observed for name in self._names(p)]
        self._observed = np.array([ids[n] for n in self.observation_names], dtype=np.intp)
        self._signal_values = self.sim.signal_values
        inputs = self.sim.input_ids
        unknown = [a for a in acted if a not in inputs]
        if unknown:
            self.sim.input(unknown[0])  # raises the kernel's "did you mean"
        self.action_names = acted
        self._acted = np.array([inputs[a] for a in acted], dtype=np.intp)
        low = np.broadcast_to(np.asarray(action_low, dtype=np.float64), (len(acted),))
        high = np.broadcast_to(np.asarray(action_high, dtype=np.float64), (len(acted),))
        if not np.all(low <= high):
            raise UsageError(f"action_low {low.tolist()} must not exceed action_high "
                             f"{high.tolist()}")
        self.action_space = _box(low, high)
        size = len(self.observation_names)
        self.observation_space = _box(np.full(size, -np.inf), np.full(size, np.inf))
        period = self.sim.control_period if control_period is None else control_period
        self.period_ticks = max(1, int(round(period / self.sim.tick_s)))
        self.max_steps = max_steps
        self._reward, self._terminated = reward, terminated
        if gymnasium is None:
            self.np_random = np.random.default_rng()
        self.steps = 0

    def _names(self, pattern):
        names = self.sim.signal_names(pattern)
        if not names:
            self.sim.signals(pattern)  # raises, naming the pattern (and a close name)
        return names

    def observe(self):
        """The current observation (a copy, in observation_names order)."""
        return self._signal_values[self._observed]

    def _seed(self, seed):
        if gymnasium is not None:
            super().reset(seed=seed)  # gymnasium's self.np_random
        elif seed is not None:
            self.np_random = np.random.default_rng(seed)
        if seed is not None:
            self.action_space.seed(seed + 1)

    def start(self, options):
        """What an episode does after the reset, before its first observation (override)."""

    def reset(self, *, seed=None, options=None):
        self._seed(seed)
        self.sim.reset(seed=seed)
        self.steps = 0
        info = self.start(options) or {}
        info["time"] = self.sim.time
        return self.observe(), info

    def apply(self, action):
        """Sets the inputs from an action (clipped to the action space)."""
        action = np.asarray(action, dtype=np.float64).reshape(-1)
        if action.shape != (len(self.action_names),):
            raise UsageError(f"an action has {len(self.action_names)} values "
                             f"({', '.join(self.action_names)}), got shape {action.shape}")
        values = np.array(self.sim.input_values)
        values[self._acted] = np.clip(action, self.action_space.low, self.action_space.high)
        self.sim.set_inputs(values)
        return action

    def step(self, action):
        action = self.apply(action)
        self.sim.step(self.period_ticks)  # the GIL is released meanwhile
        self.steps += 1
        obs = self.observe()
        reward = float(self._reward(self, obs, action)) if self._reward else 0.0
        terminated = bool(self._terminated(self, obs)) if self._terminated else False
        truncated = self.max_steps is not None and self.steps >= self.max_steps
        return obs, reward, terminated, truncated, {"time": self.sim.time}

    def close(self):
        self.sim = None


class CartPoleEnv(SimulationEnv):
    """scenes/cartpole: one action per 20 ms control period, a force on the cart in [-10, 10]
    N; the observation is (cart x [m], cart speed [m/s], pole pitch [rad], pitch rate [rad/s]);
    reward 1 per step while the pole is within 0.4 rad of vertical and the cart within 1.5 m;
    truncated after 500 steps (10 s). An episode starts with a random push (up to 2 N for
    0.1 s) drawn from the reset's seed."""

    max_force_N = 10.0
    pole_limit_rad, cart_limit_m = 0.4, 1.5
    FORCE = "robots/cartpole/axes/slide/ref_torque"
    OBSERVED = ["robots/cartpole/axes/slide/pos", "robots/cartpole/axes/slide/speed",
                "robots/cartpole/solids/pole/pitch", "robots/cartpole/solids/pole/wy"]

    def __init__(self, scene=None, tilt_deg=0.0, max_steps=500, **simulation):
        if scene is None:
            scene = os.path.join(PACKAGE_SCENES, "cartpole")
        defines = dict(simulation.pop("defines", {}))
        defines.setdefault("tilt_deg", tilt_deg)
        super().__init__(scene, self.OBSERVED, [self.FORCE], -self.max_force_N, self.max_force_N,
                         max_steps=max_steps, reward=CartPoleEnv._reward_of,
                         terminated=CartPoleEnv._fallen, defines=defines, **simulation)

    @staticmethod
    def _fallen(env, obs):
        return abs(obs[2]) > env.pole_limit_rad or abs(obs[0]) > env.cart_limit_m

    @staticmethod
    def _reward_of(env, obs, action):
        return 0.0 if CartPoleEnv._fallen(env, obs) else 1.0

    def start(self, options):
        push = float(self.np_random.uniform(-2.0, 2.0))  # N for 0.1 s: a start near upright
        self.sim.set_input(self.FORCE, push)
        self.sim.step(5 * self.period_ticks)
        self.sim.set_input(self.FORCE, 0.0)
        return {"push_N": push}


#: The ids registered with gymnasium, and what they make.
ENVIRONMENTS = {
    "s2sim/Scene-v0": "s2sim.envs:SimulationEnv",
    "s2sim/CartPole-v0": "s2sim.envs:CartPoleEnv",
}


def register_envs(gym=None):
    """Registers ENVIRONMENTS with gymnasium (or ``gym``, a module with its ``register`` and
    ``registry``); the ids registered, none without gymnasium. Gymnasium's plugin entry point
    (``gymnasium.envs``) calls it; ``import s2sim.envs`` does too."""
    gym = gym if gym is not None else gymnasium
    if gym is None:
        return []
    done = []
    for env_id, entry_point in ENVIRONMENTS.items():
        if env_id not in gym.registry:
            gym.register(id=env_id, entry_point=entry_point)
        done.append(env_id)
    return done


register_envs()
