import sys, json
sys.path.insert(0,'/work/tools')
import drivedyn
from small import small
model = sys.argv[1]; ex = json.loads(sys.argv[2]) if len(sys.argv) > 2 else {}
m = drivedyn.replace(small(2000.0, amp=0.0), {'belt.segments': 452} if model == 'segments' else {'simulation.model': 'rotational'})
m = drivedyn.replace(m, ex)
r = drivedyn.run(m)
print(model, ex, {p: round(100*v['slip'],4) for p, v in r.summary['pulleys'].items()}, {s: (round(v['tension_min'],1), round(v['tension_max'],1)) for s, v in r.summary['spans'].items()})
