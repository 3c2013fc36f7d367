#!/usr/bin/env python3
"""ppo-tutor's native CartPole against Gymnasium's, side by side, same machine.

Alternates, --rounds times: the peer script gym_speed.py (Gymnasium's gym.make("CartPole-v1"),
the bare CartPoleEnv and the numpy CartPoleVectorEnv(256)), then `cargo bench --bench cartpole`
(criterion: one env, 256 envs). Prints a Markdown table of the medians and the ratios
(min, median, max over the rounds), with the sin/cos backend the bench reports.

usage: python3 benches/cartpole_vs_gym.py --peer PATH/gym_speed.py --python PEER_VENV/bin/python \
           [--rounds 3] [--measurement-time 5]

The peer needs gymnasium==1.4.0 and numpy. Run from the repository root.
"""
import argparse, json, pathlib, re, statistics, subprocess, sys

BENCHES = {'single': 'single_env_steps', 'vector': 'vector256_env_steps'}


def gym_round(python, peer):
    out = subprocess.run([python, peer], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def ours_round(measurement_time):
    cmd = ['cargo', 'bench', '--bench', 'cartpole', '--', '--warm-up-time', '2',
           '--measurement-time', str(measurement_time), 'cartpole/']
    run = subprocess.run(cmd, check=True, capture_output=True, text=True)
    backend = re.search(r'sin/cos backend: (.*)', run.stderr + run.stdout)
    rates = {}
    for key, name in BENCHES.items():
        base = pathlib.Path('target/criterion/cartpole') / name / 'new'
        median_ns = json.loads((base / 'estimates.json').read_text())['median']['point_estimate']
        elements = json.loads((base / 'benchmark.json').read_text())['throughput']['Elements']
        rates[key] = elements / (median_ns * 1e-9)
    return rates, backend.group(1) if backend else 'unknown'


def spread(values):
    return f"{min(values):.1f} / {statistics.median(values):.1f} / {max(values):.1f}"


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--peer', required=True, help='path to gym_speed.py')
    p.add_argument('--python', default=sys.executable, help='python with gymnasium + numpy')
    p.add_argument('--rounds', type=int, default=3)
    p.add_argument('--measurement-time', type=int, default=5)
    a = p.parse_args()
    gyms, ours, backend = [], [], 'unknown'
    for r in range(a.rounds):
        gyms.append(gym_round(a.python, a.peer))
        rates, backend = ours_round(a.measurement_time)
        ours.append(rates)
        print(f"round {r + 1}: gym {gyms[-1]}, ppo-tutor "
              f"{ {k: round(v) for k, v in rates.items()} }", file=sys.stderr)
    make = [g['make_steps_per_s'] for g in gyms]
    bare = [g['bare_steps_per_s'] for g in gyms]
    vec = [g['vector256_steps_per_s'] for g in gyms]
    single = [o['single'] for o in ours]
    vector = [o['vector'] for o in ours]
    m = statistics.median
    print(f"sin/cos: {backend}; {a.rounds} rounds, alternating\n")
    print("| environment | steps/s (median) | ppo-tutor ÷ Gymnasium (min / median / max) |")
    print("|---|---:|---:|")
    print(f"| Gymnasium `gym.make(\"CartPole-v1\")` | {m(make) / 1e3:.0f}k | |")
    print(f"| Gymnasium bare `CartPoleEnv` | {m(bare) / 1e3:.0f}k | |")
    print(f"| Gymnasium numpy `CartPoleVectorEnv(256)` | {m(vec) / 1e6:.2f}M | |")
    print(f"| ppo-tutor `CartPole`, one env | {m(single) / 1e6:.1f}M | "
          f"{spread([s / g for s, g in zip(single, make)])}x `gym.make` |")
    print(f"| ppo-tutor `CartPoleVec`, 256 envs, one core | {m(vector) / 1e6:.1f}M | "
          f"{spread([v / g for v, g in zip(vector, vec)])}x numpy vector |")


if __name__ == '__main__':
    main()
