#!/usr/bin/env python3
"""ppo-tutor's candle PPO against the seed's PyTorch PPO, side by side, same machine.

Runs the full default training of both programs for each seed, one after the other, and
prints a Markdown table: wall time, env steps per second, peak resident memory (from wait4,
the process and anything it waited for), and the mean return of the last episodes, then
the ratios and the load average before and after (state it with the figures: a loaded
machine slows PyTorch far more than ppo-tutor).

- CartPole-v1 (default): the seed's PPO, 500 episodes, mean of the last 50 returns; the
  peer is seed_ppo.py.
- `--env Pendulum-v1`: the book's PPOContinuous, 2000 episodes, mean of the last 100; the
  peer is book_ppo_continuous.py (it imports seed_ppo.py from its own folder).

usage: python3 benches/ppo_vs_pytorch.py --peer PATH/seed_ppo.py --python PEER_VENV/bin/python \
           [--seeds 0-3] [--episodes 500] [--bin target/release/ppo-tutor] [--out results.json]
       python3 benches/ppo_vs_pytorch.py --env Pendulum-v1 --peer PATH/book_ppo_continuous.py \
           --python PEER_VENV/bin/python [--seeds 0-4] [--episodes 2000]

The peer needs gymnasium==1.4.0, torch and numpy (see the peer's README); seed_ppo.py runs
with --threads 1 (torch.set_num_threads(1)). Build ppo-tutor first: cargo build --release.
"""
import argparse, json, os, statistics, subprocess, sys, tempfile, time


def seeds(spec):
    lo, _, hi = spec.partition('-')
    return list(range(int(lo), int(hi or lo) + 1))


def run(cmd, json_path):
    """Runs cmd, returns (its --json document, wall seconds, peak RSS in MB)."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    err = proc.stderr.read().decode(errors='replace')
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{err}")
    with open(json_path) as f:
        doc = json.load(f)
    return doc, wall, usage.ru_maxrss / 1024.0  # Linux reports KB


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--peer', required=True, help='path to seed_ppo.py')
    p.add_argument('--python', default=sys.executable, help='python with torch + gymnasium')
    p.add_argument('--bin', default='target/release/ppo-tutor')
    p.add_argument('--seeds', default='0-3')
    p.add_argument('--episodes', type=int, help='default: 500 (CartPole-v1), 2000 (Pendulum-v1)')
    p.add_argument('--env', default='CartPole-v1', choices=['CartPole-v1', 'Pendulum-v1'])
    p.add_argument('--out', help='also write every run as JSON here')
    a = p.parse_args()
    pendulum = a.env == 'Pendulum-v1'
    episodes = a.episodes or (2000 if pendulum else 500)
    last = 100 if pendulum else 50
    peer_name = 'PyTorch book' if pendulum else 'PyTorch seed'
    rows, tmp = [], tempfile.mkdtemp()
    load_before = os.getloadavg()  # others' work on the machine slows the two unequally
    for seed in seeds(a.seeds):
        for name, cmd in (
            ('ppo-tutor', [a.bin, 'train', '--quiet', '--env', a.env, '--episodes', str(episodes), '--seed', str(seed)]),
            (peer_name, [a.python, a.peer, '--episodes', str(episodes), '--seed', str(seed), '--threads', '1']),
        ):
            out = os.path.join(tmp, f'{name.split()[0]}-{seed}.json')
            doc, wall, rss = run(cmd + ['--json', out], out)
            row = dict(program=name, seed=seed, wall_s=wall, train_s=doc['wall_s'],
                       env_steps=doc['env_steps'], steps_per_s=doc['env_steps'] / doc['wall_s'],
                       peak_rss_mb=rss, mean_last=statistics.fmean(doc['returns'][-last:]))
            rows.append(row)
            print(f"{name:12} seed {seed}: {wall:7.2f} s, {row['env_steps']} steps, "
                  f"{rss:6.1f} MB, mean last {last} {row['mean_last']:.1f}", file=sys.stderr)
    if a.out:
        with open(a.out, 'w') as f:
            json.dump(rows, f, indent=1)
    print(f'| program | seed | wall time (s) | training loop (s) | env steps | env steps/s | peak RSS (MB) | mean return, last {last} |')
    print('|---|---:|---:|---:|---:|---:|---:|---:|')
    for r in rows:
        print(f"| {r['program']} | {r['seed']} | {r['wall_s']:.2f} | {r['train_s']:.2f} | {r['env_steps']} | "
              f"{r['steps_per_s']:,.0f} | {r['peak_rss_mb']:.0f} | {r['mean_last']:.1f} |")
    ours = [r for r in rows if r['program'] == 'ppo-tutor']
    theirs = [r for r in rows if r['program'] != 'ppo-tutor']
    speed = statistics.fmean(t['wall_s'] / o['wall_s'] for o, t in zip(ours, theirs))
    sps = statistics.fmean(o['steps_per_s'] / t['steps_per_s'] for o, t in zip(ours, theirs))
    print(f"\nppo-tutor is {speed:.1f}x faster in wall time per run and {sps:.1f}x in env steps/s "
          f"(mean over seeds {a.seeds}); peak RSS {statistics.fmean(r['peak_rss_mb'] for r in ours):.0f} MB "
          f"vs {statistics.fmean(r['peak_rss_mb'] for r in theirs):.0f} MB.")
    load = ', '.join(f'{x:.2f}' for x in load_before + os.getloadavg())
    print(f"Load average (1, 5, 15 min) before and after: {load} on {os.cpu_count()} CPUs.")


if __name__ == '__main__':
    main()
