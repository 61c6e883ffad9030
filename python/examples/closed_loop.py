import corsa

sim = corsa.Simulation("scenarios/cut_in.xosc", duration=20.0)  # Ego's speed comes from Python
while sim.step():
    ego, cutter = sim.state("Ego"), sim.state("Cutter")
    gap = cutter.s - ego.s - 4.6 if cutter.lane == ego.lane and cutter.s > ego.s else 1e9
    change = min(30.0, gap / 2.0) - ego.speed  # toward 2 s behind, at most 30 m/s
    sim.set_speed("Ego", ego.speed + max(-8.0 * sim.dt, min(3.0 * sim.dt, change)))
print(len(sim.collisions()), "collisions; Ego at", round(sim.state("Ego").speed, 2), "m/s")
corsa.collect("scenarios/cut_in.xosc", "scenarios/rigs/small.xml", "out/py", duration=0.3,
              force=True)  # a dataset, as `corsa run --rig` writes it
frame = corsa.Dataset("out/py")[0]
print({name: (array.shape, array.dtype.str) for name, array in frame.data.items()})
