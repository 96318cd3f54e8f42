"""Translation between unified-planning problems and the PDDL texts `logic_lfd` reads.

A problem is written with UP's own `PDDLWriter`, which may rename items (PDDL names are
lower-case and may not clash with keywords); the writer's `get_item_named` maps the planner's
actions back to the problem's actions and objects, and `get_pddl_name` maps a problem's atoms
to the PDDL atoms of a Logic-LfD state.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, List, Mapping, Optional

import unified_planning.model as up_model  # type: ignore[import-untyped]
from unified_planning.io import PDDLReader, PDDLWriter  # type: ignore[import-untyped]
from unified_planning.plans import SequentialPlan  # type: ignore[import-untyped]


@dataclass(frozen=True)
class PddlTask:
    """A problem written as PDDL: the domain and problem texts, and the writer that named them.

    The writer keeps the renaming of the problem's items, so it is the one to ask for the PDDL
    name of an atom (`atom`) or to read a plan back (`plan_of`).
    """

    problem: Any
    """The `unified_planning.model.Problem` written."""
    writer: Any
    """The `PDDLWriter` that wrote it (its renamings)."""
    domain: str
    """The PDDL domain text."""
    task: str
    """The PDDL problem text."""

    @staticmethod
    def of(problem: Any) -> PddlTask:
        """Writes `problem` with UP's `PDDLWriter` (requirements included)."""
        writer = PDDLWriter(problem)
        domain = writer.get_domain()
        task = writer.get_problem()
        return PddlTask(problem=problem, writer=writer, domain=domain, task=task)

    def plan_text(self, plan: Any) -> str:
        """A UP `SequentialPlan` of this problem as PDDL plan text, one action a line."""
        text: str = self.writer.get_plan(plan)
        return text

    def atom(self, expression: Any) -> str:
        """The PDDL atom `(name arg …)` of a ground boolean fluent expression."""
        name = self.writer.get_pddl_name(expression.fluent())
        args = [self.writer.get_pddl_name(a.object()) for a in expression.args]
        return "(" + " ".join([name, *args]) + ")"

    def plan_of(self, actions: Iterable[str], problem: Optional[Any] = None) -> Any:
        """The UP `SequentialPlan` of planner actions `(name arg …)`.

        The action instances refer to the actions and objects of `problem` (by name; the
        written problem when `None`), so a plan found on a copy applies to the original.
        """
        target = self.problem if problem is None else problem
        text = "\n".join(actions)
        if not text.strip():
            return SequentialPlan([], environment=target.environment)

        def item(name: str) -> Any:
            found = self.writer.get_item_named(name)
            if isinstance(found, up_model.Action) and target.has_action(found.name):
                return target.action(found.name)
            if isinstance(found, up_model.Object) and target.has_object(found.name):
                return target.object(found.name)
            return found

        return PDDLReader(environment=target.environment).parse_plan_string(target, text, item)


def true_atoms(task: PddlTask, values: Mapping[Any, Any]) -> List[str]:
    """The PDDL atoms of the boolean fluent expressions that are true in `values`.

    `values` maps ground fluent expressions to values (a problem's `initial_values` or a
    simulator state's); numeric values (static action costs) are not part of a state.
    """
    atoms = []
    for expression, value in values.items():
        if expression.type.is_bool_type() and value.is_true():
            atoms.append(task.atom(expression))
    return sorted(atoms)
