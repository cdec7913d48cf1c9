"""Scenario evaluation: people positions and clearance from the world file, result round trip, the table."""

import csv
import io
import math

import pytest

from flex_nav.apps.eval.metrics import RunResult, people_clearance, person_position, walking_intervals
from flex_nav.apps.eval.table import to_csv, to_markdown
from flex_nav_sim.world import load_world


def test_s3_person_stands_in_the_door_until_the_event_then_walks():
    world = load_world("s3_person_in_door")
    person = world.people[0]
    intervals = walking_intervals(person, world.events)
    assert intervals == [(25.0, math.inf)]
    assert person_position(person, intervals, 10.0) == pytest.approx((5.0, 2.0))
    assert person_position(person, intervals, 24.9) == pytest.approx((5.0, 2.0))
    x, y = person_position(person, intervals, 27.0)  # 2 s at 0.6 m/s along the first leg
    assert math.hypot(x - 5.0, y - 2.0) == pytest.approx(1.2, abs=0.01)


def test_clearance_is_centre_distance_minus_both_radii():
    world = load_world("s3_person_in_door")
    radius = world.people[0].radius
    trajectory = [(0.0, 1.5, 2.0), (5.0, 4.0, 2.0), (6.0, 3.0, 2.0)]
    assert people_clearance(world, trajectory, robot_radius_m=0.2) == pytest.approx(1.0 - radius - 0.2)
    assert people_clearance(world, trajectory[:1], goal_sim_s=1.0) == math.inf  # no sample after the goal


def test_clearance_while_moving_skips_the_samples_where_the_robot_stood():
    world = load_world("s3_person_in_door")
    radius = world.people[0].radius
    # it drives to 1.5 m from the person (at (5, 2) until 25 s), then stands at 1.0 m: the person is nearest then
    trajectory = [(0.0, 1.5, 2.0), (5.0, 3.5, 2.0), (6.0, 4.0, 2.0), (10.0, 4.0, 2.0)]
    assert people_clearance(world, trajectory, robot_radius_m=0.2) == pytest.approx(1.0 - radius - 0.2)
    moving = people_clearance(world, trajectory, robot_radius_m=0.2, moving_only=True)
    assert moving == pytest.approx(1.0 - radius - 0.2)  # it arrived at 1.0 m moving (0.5 m/s)
    standing_close = [(0.0, 1.5, 2.0), (5.0, 3.5, 2.0), (6.0, 3.5, 2.0)]
    assert people_clearance(world, standing_close, robot_radius_m=0.2, moving_only=True) == pytest.approx(
        1.5 - radius - 0.2)  # the last sample stood still: only the moving one counts
    assert people_clearance(world, [(0.0, 4.0, 2.0)], moving_only=True) == math.inf  # one sample: no speed


def test_a_world_without_people_has_infinite_clearance():
    assert people_clearance(load_world("s1_light_box_door"), [(0.0, 1.0, 1.0)]) == math.inf


def test_walker_with_a_start_time_and_a_stop_event():
    class P:
        name, walks, start_time = "p", True, 2.0

    class E:
        def __init__(self, time, action):
            self.time, self.action, self.target = time, action, "p"

    assert walking_intervals(P, [E(5.0, "stop_walking"), E(8.0, "start_walking")]) == [(2.0, 5.0), (8.0, math.inf)]


def results():
    return [
        RunResult("s1", "move_base_like", 0, success=False, note="goal given up", path_m=3.0),
        RunResult("s1", "push_or_avoid", 0, success=True, time_s=40.0, path_m=8.0, pushes_tried=1,
                  pushes_succeeded=1, heading_error_deg=-3.5),
        RunResult("s1", "push_or_avoid", 1, success=True, time_s=50.0, path_m=9.0, pushes_tried=2,
                  pushes_succeeded=1, min_people_clearance_m=0.4),
    ]


def test_result_round_trips_through_json_values():
    for result in results():
        assert RunResult.from_dict(result.to_dict()).to_dict() == result.to_dict()
    back = RunResult.from_dict(results()[0].to_dict())
    assert math.isnan(back.time_s) and back.min_people_clearance_m == math.inf and math.isnan(back.heading_error_deg)
    assert RunResult.from_dict(results()[1].to_dict()).heading_error_deg == -3.5
    recorded_before = {k: v for k, v in results()[1].to_dict().items() if k != "heading_error_deg"}
    assert math.isnan(RunResult.from_dict(recorded_before).heading_error_deg)  # older results.csv rows load


def test_csv_has_one_row_per_run_and_empty_cells_for_missing_values():
    rows = list(csv.DictReader(io.StringIO(to_csv(results()))))
    assert len(rows) == 3
    assert rows[0]["time_s"] == "" and rows[0]["success"] == "False"
    assert rows[0]["heading_error_deg"] == "" and rows[1]["heading_error_deg"] == "-3.5"
    assert rows[2]["pushes_tried"] == "2"


def test_markdown_summarises_per_scenario_and_behavior():
    text = to_markdown(results())
    lines = text.splitlines()
    assert lines[0].startswith("| scenario | behavior | success | time to goal [s]")
    assert "| s1 | move_base_like | 0/1 | - | - | 0/0 | 0 | - |" in lines
    assert "| s1 | push_or_avoid | 2/2 | 45.0 | 8.5 | 3/2 | 0 | 0.40 |" in lines
    assert "s1 / move_base_like / seed 0: goal given up" in text


def test_contacts_with_people_are_split_by_whose_doing_they_were():
    from flex_nav.apps.eval.metrics import classify_contact  # noqa: PLC0415

    facing_north = (2.0, 3.0, math.pi / 2.0)  # the robot at (2, 3) facing +y
    ahead = (2.0, 3.17)  # touched at its front
    assert classify_contact(facing_north, 0.2, 0.0, ahead).robot_caused  # drove into the person
    assert not classify_contact(facing_north, 0.0, 0.0, ahead).robot_caused  # stood: the person walked into it
    assert not classify_contact(facing_north, -0.2, 0.0, ahead).robot_caused  # backed away: walked into it
    behind = (2.0, 2.83)
    assert classify_contact(facing_north, -0.2, 0.0, behind).robot_caused  # backed into the person
    assert not classify_contact(facing_north, 0.2, 0.0, behind).robot_caused  # drove away: walked into its back
    with pytest.raises(ValueError, match="no direction"):
        classify_contact(facing_north, 0.2, 0.0, (2.0, 3.0))


def test_the_contact_split_round_trips_and_older_results_load_without_it():
    result = RunResult("s6", "push_or_avoid", 0, success=True, time_s=46.7, people_contacts=3,
                       people_contacts_robot_caused=1, people_contacts_person_caused=2)
    back = RunResult.from_dict(result.to_dict())
    assert (back.people_contacts, back.people_contacts_robot_caused, back.people_contacts_person_caused) == (3, 1, 2)
    recorded_before = {k: v for k, v in result.to_dict().items() if not k.startswith("people_contacts_")}
    older = RunResult.from_dict(recorded_before)
    assert (older.people_contacts, older.people_contacts_robot_caused, older.people_contacts_person_caused) == (3, 0, 0)
    rows = list(csv.DictReader(io.StringIO(to_csv([result]))))
    assert rows[0]["people_contacts_robot_caused"] == "1" and rows[0]["people_contacts_person_caused"] == "2"


def test_the_table_says_how_many_contacts_were_the_robots_doing():
    classified = [RunResult("s6", "push_or_avoid", s, success=True, time_s=45.0, path_m=8.6, people_contacts=c,
                            people_contacts_robot_caused=r, people_contacts_person_caused=c - r)
                  for s, c, r in ((0, 2, 0), (1, 1, 1))]
    lines = to_markdown(classified).splitlines()
    assert "| s6 | push_or_avoid | 2/2 | 45.0 | 8.6 | 0/0 | 3 (1 by the robot) | - |" in lines
    unclassified = [RunResult("s6", "move_base_like", 0, success=True, time_s=58.0, path_m=9.0, people_contacts=4)]
    assert "| s6 | move_base_like | 1/1 | 58.0 | 9.0 | 0/0 | 4 | - |" in to_markdown(unclassified).splitlines()


def test_a_standing_robot_shoved_by_a_walker_is_not_moving():
    from flex_nav.apps.eval.metrics import commanded_at  # noqa: PLC0415

    world = load_world("s3_person_in_door")  # the person stands at (5, 2) until 25 s
    radius = world.people[0].radius
    # driven to 1.0 m from the person's centre, stopped there at 6 s, then shoved 0.5 m toward them at 9-10 s
    trajectory = [(0.0, 1.5, 2.0), (5.0, 3.5, 2.0), (6.0, 4.0, 2.0), (9.0, 4.0, 2.0), (10.0, 4.5, 2.0)]
    commands = [(0.0, 0.3), (5.5, 0.2), (6.0, 0.0), (9.5, 0.0)]
    shoved = people_clearance(world, trajectory, robot_radius_m=0.2, moving_only=True)
    assert shoved == pytest.approx(0.5 - radius - 0.2)  # ground truth alone: it "moved" at 0.5 m
    own = people_clearance(world, trajectory, robot_radius_m=0.2, moving_only=True, commands=commands)
    assert own == pytest.approx(1.0 - radius - 0.2)  # it moved on its own only up to 1.0 m
    assert commanded_at(commands, 6.0) and commanded_at(commands, 6.1)  # braking after its last moving command
    assert not commanded_at(commands, 6.3) and not commanded_at(commands, 10.0) and not commanded_at([], 1.0)


def test_clearance_counts_the_peoples_walks_from_the_worlds_start():
    """A world whose script started at 4 s (lockstep, /sim/start_world): the person leaves the door at 25 s of the
    world's time, i.e. 29 s of simulated time; the same passage 4 s later gives the same clearance."""
    world = load_world("s3_person_in_door")
    passing = [(26.0, 5.0, 3.0), (27.0, 5.5, 3.0)]  # the person walks from (5, 2) from 25 s on
    shifted = [(t + 4.0, x, y) for t, x, y in passing]
    at_zero = people_clearance(world, passing)
    assert people_clearance(world, shifted, world_start_s=4.0) == pytest.approx(at_zero)
    assert people_clearance(world, shifted) != pytest.approx(at_zero)  # counted from 0 the person is elsewhere
