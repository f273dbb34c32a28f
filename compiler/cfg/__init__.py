"""The analysis library over the IR's control-flow graphs (issue 26): one implementation of each
question that lint, the structurer, the optimizer and the move-mode and in-force analyses ask.

One module per job, all over a plain graph: nodes numbered 0..n-1 and `succ[i]`, node i's
successors in order. A `BlockIndex` numbers a routine's blocks (or any labelled nodes: the
structurer adds a virtual exit) and maps the numbers back to labels; lists indexed by number keep
the walks fast and linear where dictionaries keyed by label strings were not (issue 26).

- `graph`: the block index of a routine (its local successors), predecessors, the depth-first
  walk (preorder, reverse postorder, retreating edges) and `all_paths_reach`;
- `dominators`: immediate dominators (Cooper, Harvey and Kennedy) and the dominator tree with a
  constant-time `dominates`;
- `loops`: back edges, natural loops, reducibility and the loop-nesting forest (Havlak);
- `dataflow`: one worklist solver to a fixed point, forward or backward, in the order given;
- `components`: strongly connected components (Tarjan), over any hashable nodes (call graphs).

Everything walks with explicit stacks and worklists (no Python recursion) and takes time linear in
the graph (the dominator iteration and the solver: a few passes for the graphs programs have).
It imports nothing but the IR: it is the layer between the IR and its users (pyproject
`[tool.importlinter]`, contract "analyses-below-their-users").
"""
