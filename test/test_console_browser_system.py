"""The operator console in a real browser: headless Debian Chromium driven by Selenium against the demo's stack.

One stack for the whole module (module-scoped fixture: a private master, the simulator, one TurtleBot 2 running
flex_planner at autonomy Low, and the console node bound to 0.0.0.0 with a token). The tests run in file order and
follow one behavior's life: a wrong token is refused; the graph shows and the active state changes; a lock holds a
state, whose userdata (the goal it wrote) the panel beside the graph shows, until the unlock; an outcome is forced;
the approve button sends the plan on and the robot moves (ground-truth odometry); preempt stops it; starts with bad
parameters show the console's and the runner's errors; a goal placed by clicking the map is reached; a heavy obstacle
marked in the robot's obstacle memory is drawn on the map and forgotten with the console's button. Every wait is
bounded; the robot's motion is read from ROS, not from the page.
"""

from __future__ import annotations

import contextlib
import math
import threading
import time
from pathlib import Path
from typing import Any, Iterator, List, Optional, Tuple

import pytest

from flex_nav.exceptions import NotReadyError
from flex_nav.testing.browser import HeadlessBrowser
from flex_nav.testing.private_master import free_port
from flex_nav.testing.process import ManagedProcess

WAIT_S = 60.0  # [s] wall bound of one wait for the page or the robot
TOKEN = "browser-test-token-0123456789"  # [chars] >= 16: the console is bound to 0.0.0.0
ROBOT = "/robot1/behavior_runner"
pytestmark = [pytest.mark.ros]
MOVING_MPS = 0.1  # [m/s] ground-truth speed that counts as driving
STOPPED_MPS = 0.02  # [m/s] ground-truth speed that counts as standing


class Stack:
    """The running demo stack, the console's URL, the browser and what the test reads from ROS."""

    def __init__(self, url: str, browser: HeadlessBrowser, monitor: Any, log_dir: Path) -> None:
        self.url = url
        self.browser = browser
        self.monitor = monitor
        self.log_dir = log_dir
        self.lock = threading.Lock()
        self.odometry: List[Tuple[float, float, float, float]] = []  # (wall [s], x [m], y [m], v [m/s])

    def on_odometry(self, msg: Any) -> None:
        p = msg.pose.pose.position
        with self.lock:
            self.odometry.append((time.monotonic(), p.x, p.y, abs(msg.twist.twist.linear.x)))
            del self.odometry[:-2000]

    def latest(self) -> Optional[Tuple[float, float, float, float]]:
        with self.lock:
            return self.odometry[-1] if self.odometry else None

    def wait(self, probe: Any, what: str, timeout_s: float = WAIT_S) -> Any:
        try:
            return self.browser.wait_for(probe, what, timeout_s)
        except NotReadyError as err:
            pytest.fail(f"{err}; page status {self.text('status')!r}, requests {self.text('requests')!r}, "
                        f"feedback {self.feedback_texts()!r}; logs in {self.log_dir}")

    def text(self, element_id: str) -> str:
        return str(self.browser.script(f"const n = document.getElementById({element_id!r}); "
                                       "return n ? n.textContent : '';"))

    def feedback_texts(self) -> List[str]:
        return list(self.browser.script(
            "return [...document.querySelectorAll('.feedback')].map((n) => n.textContent).filter((t) => t);"))

    def active(self) -> List[str]:
        return list(self.browser.script("return [...document.querySelectorAll('#graph .active')].map((n) => n.id);"))

    def click(self, css: str) -> None:
        from selenium.webdriver.common.by import By  # noqa: PLC0415

        self.browser.driver.find_element(By.CSS_SELECTOR, css).click()

    def click_button(self, container: str, text: str) -> None:
        """Click the button of ``container`` whose label is ``text`` (waits for it to exist)."""
        from selenium.webdriver.common.by import By  # noqa: PLC0415

        def find() -> Any:
            for button in self.browser.driver.find_elements(By.CSS_SELECTOR, f"{container} button"):
                if button.text.strip() == text and button.is_enabled():
                    return button
            return None

        self.wait(find, f"button {text!r} in {container}").click()

    def feedback(self, name: str) -> str:
        return str(self.browser.script(
            f"const n = document.querySelector('[data-feedback=\"{name}\"]'); return n ? n.textContent : '';"))


@pytest.fixture(scope="module")
def stack(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Stack]:
    import rospy  # noqa: PLC0415 - only once the master is up
    from nav_msgs.msg import Odometry  # noqa: PLC0415

    from flex_nav.apps import nav_demo  # noqa: PLC0415
    from flex_nav.ros.node import init_node  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    out = tmp_path_factory.mktemp("console_browser")
    args = nav_demo.parse_args(["--autonomy", "low", "--goals", "g1", "--rtf", "1.0", "--out", str(out)])
    runs = nav_demo.plan_robots(load_world(args.world), args.profile_list, 1, ["g1"])
    port = free_port()
    with contextlib.ExitStack() as exits:
        processes, env = nav_demo.start_system(exits, args, runs, out, bag=False)
        console = ManagedProcess(["rosrun", "flex_nav", "console", "_host:=0.0.0.0", f"_port:={port}",
                                  f"_token:={TOKEN}", "_discovery_period_s:=0.5"],
                                 env=env, log_path=out / "logs" / "console.log")
        exits.callback(console.stop)
        init_node("console_browser_test", anonymous=True)
        exits.callback(rospy.signal_shutdown, "the browser tests are done")
        monitor = nav_demo.DemoMonitor(runs)
        browser = exits.enter_context(HeadlessBrowser())
        test_stack = Stack(f"http://127.0.0.1:{port}/", browser, monitor, out / "logs")
        rospy.Subscriber("/robot1/ground_truth", Odometry, test_stack.on_odometry, queue_size=20)
        problem = nav_demo.wait_until_ready(monitor, [*processes, console])
        assert problem is None, f"the stack did not start: {problem}"
        yield test_stack


def test_a_wrong_token_is_refused(stack: Stack) -> None:
    driver = stack.browser.driver
    driver.delete_all_cookies()
    driver.get(stack.url)
    assert "a token is needed" in driver.find_element("tag name", "body").text
    driver.get(stack.url + "?token=" + "x" * len(TOKEN))
    assert "wrong token" in driver.find_element("tag name", "body").text
    assert not driver.get_cookies()
    driver.get(stack.url + "?token=" + TOKEN)  # the right one: a cookie, and the page
    assert driver.current_url == stack.url
    stack.wait(lambda: stack.text("connection") == "connected", "the page's websocket connected")


def test_the_graph_shows_and_the_active_state_changes(stack: Stack) -> None:
    stack.wait(lambda: stack.browser.script("return document.querySelectorAll('#graph svg g.node').length > 5"),
               "the behavior's graph drawn")
    assert stack.text("behavior-name") == "flex_planner"
    stack.wait(lambda: stack.active() == ["st-ReceiveGoal"], "ReceiveGoal shown active")
    assert stack.text("status").startswith("RUNNING")


def test_a_lock_holds_the_state(stack: Stack) -> None:
    stack.click("#st-ReceiveGoal")
    stack.wait(lambda: "/ReceiveGoal" in stack.text("selected"), "ReceiveGoal selected")
    stack.click('[data-command="lock"]')
    stack.wait(lambda: stack.feedback("state").startswith("ok"), "the runner's answer to lock")
    stack.monitor.send_due_goals()  # the goal arrives: ReceiveGoal would leave with 'received', but it is locked
    stack.wait(lambda: "waits for an unlock" in stack.text("requests"), "the locked outcome shown waiting")
    assert stack.active() == ["st-ReceiveGoal"]


def test_the_userdata_of_the_held_state_shows_the_goal_it_wrote(stack: Stack) -> None:
    # ReceiveGoal (selected, held by the lock) wrote its output key goal: the runner's ~userdata carries it and the
    # panel beside the graph shows it, summarized (the goal the monitor sent: g1 of the lab world)
    goal = stack.monitor.runs[0].goals[0][1]
    shown = stack.wait(lambda: stack.browser.script(
        "const box = document.getElementById('userdata'); const h = box.querySelector('h3');"
        "const v = box.querySelector('dd[data-key=\"goal\"]');"
        "return h && v ? [h.textContent, v.previousElementSibling.textContent, v.textContent] : null;"),
        "ReceiveGoal's goal in the userdata panel")
    assert shown[0] == "/ReceiveGoal" and shown[1] == "goal out", shown
    assert shown[2].startswith('geometry_msgs/PoseStamped frame="map" x='), shown
    fields = dict(part.split("=", 1) for part in shown[2].split()[1:])
    assert math.dist((float(fields["x"]), float(fields["y"])), goal[:2]) < 0.01, (shown, goal)
    assert float(fields["yaw_deg"]) == pytest.approx(math.degrees(goal[2]), abs=0.5), (shown, goal)


def test_the_unlock_lets_the_state_go(stack: Stack) -> None:
    stack.click('[data-command="unlock"]')
    stack.wait(lambda: stack.active() == ["st-ApprovePlan"], "ApprovePlan active after the unlock", 30.0)


def test_a_forced_outcome(stack: Stack) -> None:
    stack.wait(lambda: "needs autonomy above HIGH" in stack.text("requests"), "ApprovePlan waiting at Low")
    stack.click_button("#requests", "select")
    stack.wait(lambda: "/ApprovePlan" in stack.text("selected"), "ApprovePlan selected")
    stack.click_button("#force-buttons", "force replan")
    stack.wait(lambda: stack.browser.script(
        "return [...document.querySelectorAll('#transitions li.forced')].some((n) => "
        "n.textContent.includes('/ApprovePlan --replan') && n.textContent.includes('GetPath (forced)'))"),
        "the forced transition listed")
    stack.wait(lambda: stack.active() == ["st-ApprovePlan"], "the new plan waiting for approval again", 30.0)
    assert stack.feedback("state").startswith("ok")


def test_approve_at_low_sends_the_plan_on_and_the_robot_moves(stack: Stack) -> None:
    start = stack.latest()
    assert start is not None, "no ground-truth odometry"
    time.sleep(1.0)  # held: nothing moves before the approval
    held = stack.latest()
    assert held is not None and held[3] < STOPPED_MPS and math.dist(start[1:3], held[1:3]) < 0.02
    stack.click_button("#requests", "approve execute")
    stack.wait(lambda: stack.active() and stack.active()[0].startswith("st-Navigate"), "Navigate active", 30.0)
    stack.wait(lambda: (stack.latest() or start)[3] > MOVING_MPS, "the robot driving (ground truth)")
    stack.wait(lambda: math.dist(start[1:3], (stack.latest() or start)[1:3]) > 0.3, "the robot 0.3 m on")


def test_preempt_stops_the_robot(stack: Stack) -> None:
    stack.wait(lambda: (stack.latest() or (0, 0, 0, 0.0))[3] > 0.3, "the robot at speed before the preempt")
    stack.click('[data-command="preempt"]')
    stack.wait(lambda: stack.text("status").startswith("PREEMPTED"), "status PREEMPTED shown", 20.0)
    stack.wait(lambda: (stack.latest() or (0, 0, 0, 1.0))[3] < STOPPED_MPS, "the robot stopped", 10.0)
    time.sleep(1.0)
    with stack.lock:
        since = [v for t, _x, _y, v in stack.odometry if t > time.monotonic() - 1.0]
    assert since and max(since) < STOPPED_MPS, f"moving again after the preempt: {max(since):.3f} m/s"


def _set_parameter(stack: Stack, name: str, value: str) -> None:
    from selenium.webdriver.common.by import By  # noqa: PLC0415

    field = stack.browser.driver.find_element(By.CSS_SELECTOR, f'[data-parameter="{name}"]')
    field.clear()
    field.send_keys(value)


def test_starts_with_bad_parameters_show_the_errors(stack: Stack) -> None:
    from selenium.webdriver.common.by import By  # noqa: PLC0415
    from selenium.webdriver.support.select import Select  # noqa: PLC0415

    Select(stack.browser.driver.find_element(By.ID, "start-behavior")).select_by_value("flex_planner")
    _set_parameter(stack, "backup_offset_m", "0.5")  # its max is -0.01: the console's validator refuses it
    stack.click('#start-form button[type="submit"]')
    stack.wait(lambda: "above its maximum" in stack.feedback("start"), "the console's refusal shown")
    assert stack.feedback("start").startswith("refused by the console: parameter 'backup_offset_m'")
    _set_parameter(stack, "backup_offset_m", "-0.2")
    _set_parameter(stack, "navigate", "no_such_navigate")  # a string: only the runner's load finds it wrong
    stack.click('#start-form button[type="submit"]')
    stack.wait(lambda: stack.feedback("start").startswith("refused:") and "no_such_navigate" in
               stack.feedback("start"), "the runner's refusal shown", 30.0)
    assert stack.text("status").startswith("PREEMPTED")


def _colour_pixels(stack: Stack, rgb: Tuple[int, int, int]) -> int:
    """How many pixels of the map's canvas have colour ``rgb``, give or take 24 a channel (antialiased lines)."""
    return int(stack.browser.script(
        "const c = document.getElementById('map'); const d = c.getContext('2d').getImageData(0, 0, c.width, "
        "c.height).data; let n = 0; for (let i = 0; i < d.length; i += 4) { if (Math.abs(d[i] - arguments[0]) "
        "<= 24 && Math.abs(d[i + 1] - arguments[1]) <= 24 && Math.abs(d[i + 2] - arguments[2]) <= 24) n++; } "
        "return n;", *rgb))


def _on_canvas(stack: Stack, canvas: Any, point: Tuple[float, float]) -> Tuple[int, int]:
    """Selenium's offset (CSS pixels from the element's centre) of map point (x, y) [m] on the map's canvas, the
    canvas scrolled wholly into view first (an action's offset counts from the centre of the element's visible
    part, W3C's in-view centre)."""
    import json  # noqa: PLC0415

    stack.browser.script("arguments[0].scrollIntoView({block: 'center'});", canvas)
    view = json.loads(canvas.get_attribute("data-view"))
    pixels = stack.browser.script("const c = document.getElementById('map'); return [c.width, c.height];")
    width, height = canvas.size["width"], canvas.size["height"]
    cx = (view["left"] + (point[0] - view["ox"]) * view["k"]) * width / pixels[0] - width / 2
    cy = (view["bottom"] - (point[1] - view["oy"]) * view["k"]) * height / pixels[1] - height / 2
    return round(cx), round(cy)


def test_a_goal_placed_by_clicking_the_map_is_reached(stack: Stack) -> None:
    import json  # noqa: PLC0415

    from selenium.webdriver.common.action_chains import ActionChains  # noqa: PLC0415
    from selenium.webdriver.common.actions.wheel_input import ScrollOrigin  # noqa: PLC0415
    from selenium.webdriver.common.by import By  # noqa: PLC0415

    _set_parameter(stack, "navigate", "flex_navigate")
    from selenium.webdriver.support.select import Select  # noqa: PLC0415

    Select(stack.browser.driver.find_element(By.ID, "start-autonomy")).select_by_value("full")
    stack.click('#start-form button[type="submit"]')
    stack.wait(lambda: stack.feedback("start").startswith("ok:"), "the runner started flex_planner", 30.0)
    stack.wait(lambda: stack.active() == ["st-ReceiveGoal"], "ReceiveGoal active in the new run", 30.0)
    stack.wait(lambda: stack.text("map-info").startswith("map "), "the map shown")
    stack.wait(lambda: _colour_pixels(stack, (0xD3, 0x2F, 0x2F)) > 20, "the scan drawn on the map")
    with stack.lock:
        home = stack.odometry[0][1:3]  # where the robot started: free, and away from where the preempt left it
    here = stack.latest()
    assert here is not None and math.dist(home, here[1:3]) > 0.3, "the robot should be away from its start"
    canvas = stack.browser.driver.find_element(By.ID, "map")
    fitted = json.loads(canvas.get_attribute("data-view"))["k"]
    x, y = _on_canvas(stack, canvas, home)
    ActionChains(stack.browser.driver).scroll_from_origin(ScrollOrigin.from_element(canvas, x, y), 0, -100) \
        .perform()  # zoom in about the robot's start: the goal is placed on the zoomed map
    stack.wait(lambda: json.loads(canvas.get_attribute("data-view"))["k"] > fitted * 1.2, "the map zoomed in")
    x, y = _on_canvas(stack, canvas, home)
    ActionChains(stack.browser.driver).move_to_element_with_offset(canvas, x, y).click_and_hold() \
        .move_by_offset(-20, 0).release().perform()  # pulled west: the goal faces west
    stack.wait(lambda: stack.feedback("map").startswith("goal sent to /robot1/behavior_runner"), "the goal sent")
    sent = stack.feedback("map")
    placed = [float(v) for v in sent.split("(")[1].split(")")[0].split(",")]
    assert math.dist(placed, home) < 0.1, f"{sent}: placed off {home} (view {canvas.get_attribute('data-view')})"
    assert sent.endswith(", 180 deg"), sent
    def plan_to_the_goal() -> bool:
        drawn = json.loads(canvas.get_attribute("data-drawn") or "{}").get(ROBOT, {}).get("global_plan")
        return bool(drawn) and drawn[0] >= 2 and math.dist(drawn[1], home) < 0.35

    stack.wait(plan_to_the_goal, "the global plan to the placed goal drawn", 30.0)
    assert _colour_pixels(stack, (0x15, 0x65, 0xC0)) > 10, "no pixel of the global plan's colour on the map"
    stack.wait(lambda: "--arrived--> Arrived" in stack.text("transitions"), "the goal reached (Arrived)", 120.0)
    end = stack.latest()
    assert end is not None, "no ground-truth odometry"
    assert math.dist(home, end[1:3]) < 0.35, f"{sent}; the robot ended at {end[1:3]}"
    drawn = json.loads(canvas.get_attribute("data-drawn") or "{}").get(ROBOT, {})
    assert drawn.get("particles", [0])[0] > 0, f"the localizer's particles not drawn: {sorted(drawn)}"
    assert math.dist(drawn["pose"][:2], end[1:3]) < 0.2, f"the robot drawn at {drawn['pose']}, truly at {end[1:3]}"
    assert drawn["pose"][2] >= 3, "the controller's footprint polygon not drawn"


def test_an_initial_pose_placed_on_the_map_reaches_the_localizer(stack: Stack) -> None:
    import json  # noqa: PLC0415

    import rospy  # noqa: PLC0415
    from geometry_msgs.msg import PoseWithCovarianceStamped  # noqa: PLC0415
    from selenium.webdriver.common.action_chains import ActionChains  # noqa: PLC0415
    from selenium.webdriver.common.by import By  # noqa: PLC0415

    received: List[Any] = []
    listener = rospy.Subscriber("/robot1/initialpose", PoseWithCovarianceStamped, received.append)
    try:
        here = stack.latest()
        assert here is not None
        stack.click('input[name="map-mode"][value="initial_pose"]')
        canvas = stack.browser.driver.find_element(By.ID, "map")
        zoomed = json.loads(canvas.get_attribute("data-view"))["k"]
        stack.click("#map-fit")
        stack.wait(lambda: json.loads(canvas.get_attribute("data-view"))["k"] < zoomed / 1.2, "the map fitted again")
        x, y = _on_canvas(stack, canvas, (here[1], here[2]))
        ActionChains(stack.browser.driver).move_to_element_with_offset(canvas, x, y) \
            .click_and_hold().move_by_offset(0, -20).release().perform()  # pulled north: facing +y
        stack.wait(lambda: stack.feedback("map").startswith("initial pose sent to /robot1/behavior_runner"),
                   "the initial pose sent", 20.0)
        stack.wait(lambda: bool(received), "the initial pose on /robot1/initialpose", 10.0)
        pose = received[-1].pose.pose
        assert received[-1].header.frame_id == "map"
        assert math.dist((pose.position.x, pose.position.y), here[1:3]) < 0.1
        assert pose.orientation.z == pytest.approx(math.sin(math.pi / 4), abs=0.05)  # yaw 90 deg
        assert received[-1].pose.covariance[0] == pytest.approx(0.25)
    finally:
        listener.unregister()


MEMORY_RGB = (0x8B, 0x00, 0x00)  # the console's remembered obstacles: dashed dark red
MEMORY_BOX_M = 0.4  # [m] side of the square footprint the test marks
MEMORY_PIXELS = 20  # the footprint's dashes make more dark red pixels than this (a 0.4 m square)
MEMORY_AWAY_M = 5.0  # [m] from the robot at least: beyond the memory's max_range_m (4 m), no scan judges it


def test_a_remembered_obstacle_is_drawn_and_forgotten_from_the_console(stack: Stack) -> None:
    """A heavy obstacle marked on the robot's obstacle_memory/mark (as push_or_avoid does; its profile, turtlebot2,
    has the memory on) is drawn on the map with its text on hover and in the list; "Forget remembered obstacles"
    calls the costmap's clear_obstacle_memory, shows its answer, and the drawing goes."""
    import json  # noqa: PLC0415

    import rospy  # noqa: PLC0415
    from geometry_msgs.msg import Point32, PolygonStamped  # noqa: PLC0415
    from selenium.webdriver.common.action_chains import ActionChains  # noqa: PLC0415
    from selenium.webdriver.common.by import By  # noqa: PLC0415

    from flex_nav.apps import nav_demo  # noqa: PLC0415
    from flex_nav_sim.world import load_world  # noqa: PLC0415

    driver = stack.browser.driver
    driver.get(stack.url + "?token=" + TOKEN)  # a fresh page (and the cookie, when this test runs alone)
    stack.wait(lambda: stack.text("connection") == "connected", "the page's websocket connected")
    canvas = driver.find_element(By.ID, "map")

    def drawn_memory() -> Any:
        return json.loads(canvas.get_attribute("data-drawn") or "{}").get(ROBOT, {}).get("memory")

    stack.wait(lambda: drawn_memory() == [0, []], "the robot's (empty) obstacle memory received by the page")
    assert stack.text("memory") == "nothing remembered"
    # other drawings' antialiased edges (a red bumper mark over a dark wall) can come near the memory's dark red:
    # the footprint is judged against what the canvas had before it
    before = _colour_pixels(stack, MEMORY_RGB)
    here = stack.wait(stack.latest, "the robot's ground-truth odometry")
    goals = [pose[:2] for pose in load_world(nav_demo.parse_args([]).world).goals.values()]
    centre = max(goals, key=lambda p: math.dist(p, here[1:3]))  # free (a goal of the world), far from the robot
    assert math.dist(centre, here[1:3]) > MEMORY_AWAY_M + MEMORY_BOX_M, (centre, here)
    half = MEMORY_BOX_M / 2
    mark = PolygonStamped()
    mark.header.frame_id = "map"
    mark.polygon.points = [Point32(x=centre[0] + dx, y=centre[1] + dy)
                           for dx, dy in ((-half, -half), (half, -half), (half, half), (-half, half))]
    marks = rospy.Publisher("/robot1/obstacle_memory/mark", PolygonStamped, queue_size=1)
    try:
        stack.wait(lambda: marks.get_num_connections() > 0, "the costmap subscribed to obstacle_memory/mark", 20.0)

        def shown() -> Any:
            if drawn_memory() and drawn_memory()[0] == 1:
                return json.loads(canvas.get_attribute("data-remembered"))
            mark.header.stamp = rospy.Time.now()
            marks.publish(mark)  # again until shown (a mark of the same place replaces the one remembered)
            time.sleep(1.0)
            return None

        (obstacle,) = stack.wait(shown, "the marked obstacle drawn on the map", 30.0)
    finally:
        marks.unregister()
    text = obstacle["text"]
    assert text.startswith("#") and f" heavy at ({centre[0]:.2f}, {centre[1]:.2f}) m, 0.40 x 0.40 m, found at " in text
    corners = sorted((round(x, 2), round(y, 2)) for x, y in obstacle["footprint"])
    assert corners == sorted((round(p.x, 2), round(p.y, 2)) for p in mark.polygon.points), corners
    stack.wait(lambda: _colour_pixels(stack, MEMORY_RGB) > before + MEMORY_PIXELS,
               "the footprint's dark red dashes on the canvas")
    stack.wait(lambda: stack.text("memory") == text, "the obstacle listed under the map")
    x, y = _on_canvas(stack, canvas, centre)
    ActionChains(driver).move_to_element_with_offset(canvas, x, y).perform()  # hover: the text as the title
    stack.wait(lambda: canvas.get_attribute("title") == text, "the obstacle's text on hover")
    stack.click("#memory-forget")
    stack.wait(lambda: stack.feedback("memory").startswith("ok:"), "the costmap's answer to forget", 20.0)
    assert stack.feedback("memory") == "ok: 1 remembered obstacle(s) forgotten"
    stack.wait(lambda: drawn_memory() == [0, []], "the forgotten obstacle gone from the page", 20.0)
    stack.wait(lambda: _colour_pixels(stack, MEMORY_RGB) <= before + MEMORY_PIXELS // 4,
               "the footprint's dark red gone from the canvas")
    assert stack.text("memory") == "nothing remembered"
    assert "← forget remembered obstacles: ok: 1 remembered obstacle(s) forgotten" in stack.text("transitions")
