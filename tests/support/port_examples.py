"""The seed's two examples as a ROS 1 user writes them, for the port's tests.

ROS Node Automator's two examples, in docs/examples: the target tracking system
(`tracker_ros1`: a detector and a mover exchanging their own message, service and action)
and the talker and listener started by one launch file (`bringup_ros1`, with a parameter).
Both are generated as catkin packages, their nodes in Python (the tiers run Python nodes;
C++ ones are reviewed against a real rclcpp outside CI), and their callbacks filled in the
way ROS 1 code is written: rospy logging with format arguments, time stamps, publishing
from a timer and from a callback, a parameter read, a service call, an action goal with
feedback. Each edit fails loudly when the starter it is anchored to changes.

`EXCHANGES` is what each node prints when the nodes really talk: the same lines before
and after the port.
"""

from __future__ import annotations

from pathlib import Path

from .generation import example
from .template_repo import replace_text


def python_variant(name: str) -> dict:
    """The example's answers with every node in Python."""
    answers = example(name)
    answers["nodes"] = [{**node, "language": "python"} for node in answers["nodes"]]
    return answers


EXAMPLES = {"bringup": python_variant("bringup_ros1"), "tracker": python_variant("tracker_ros1")}

# (node file, the starter's text, the user's) for each example; node files are ROS 1's paths.
USER_CODE = {
    "bringup": [
        ("scripts/talker.py", """        rospy.loginfo('rate: %s', self.rate)
        self.count = 0
""", """        rospy.loginfo('rate: %s', self.rate)
        self.count = 0
        self.started = rospy.Time.now()
        self.period = 1.0 / rospy.get_param('~rate', 1.0)
"""),
        ("scripts/talker.py", """        msg = String()
        msg.data = f'Hello World: {self.count}'
        rospy.loginfo_throttle(1.0, f'Publishing: "{msg.data}"')
        self.chatter_publisher.publish(msg)
        self.count += 1
""", """        msg = String()
        msg.data = 'hello %d' % self.count
        elapsed = (rospy.Time.now() - self.started).to_sec()
        rospy.loginfo('talker says %s after %.1f s at %s Hz', msg.data, elapsed, self.rate)
        self.chatter_publisher.publish(msg)
        self.count += 1
        rospy.logdebug_throttle(10.0, 'period %.2f s', self.period)
"""),
        ("scripts/listener.py", """        rospy.loginfo(f'I heard: "{msg.data}"')
""", """        self.heard = getattr(self, 'heard', 0) + 1
        rospy.loginfo('listener heard %s (%d so far)', msg.data, self.heard)
        if rospy.is_shutdown():
            rospy.logwarn('heard while shutting down')
"""),
    ],
    "tracker": [
        ("scripts/detector.py", """        msg = Target()
        self.target_publisher.publish(msg)
        self.count += 1
        self.call_set_target(SetTargetRequest())
        ready = self.approach_action_client.wait_for_server(rospy.Duration(0.01))
        if ready and not self.approach_goal_active:
            self.send_approach_goal(ApproachGoal())
""", """        msg = Target()
        msg.header.stamp = rospy.Time.now()
        msg.header.frame_id = 'map'
        msg.x = 1.0 + self.count
        msg.y = 2.0
        self.target_publisher.publish(msg)
        rospy.loginfo('detector published target %d at x=%.1f', self.count, msg.x)
        self.count += 1
        self.call_set_target(SetTargetRequest(target=msg))
        ready = self.approach_action_client.wait_for_server(rospy.Duration(0.01))
        if ready and not self.approach_goal_active:
            self.send_approach_goal(ApproachGoal(distance=1.5))
"""),
        ("scripts/detector.py", """        rospy.loginfo(f'set_target answered: {response}')
""", """        rospy.loginfo('set_target accepted: %s', response.accepted)
"""),
        ("scripts/detector.py", """        rospy.loginfo('Feedback on the approach goal')
""", """        rospy.loginfo('approach: %.1f m to go', feedback.remaining)
"""),
        ("scripts/detector.py", """            rospy.loginfo('The approach goal succeeded')
""", """            rospy.loginfo('approach done, reached: %s', result.reached)
"""),
        ("scripts/mover.py", """        rospy.loginfo('Received a message on target')
""", """        stamp = msg.header.stamp.to_sec()
        rospy.loginfo('mover got target at x=%.1f in %s (stamped %.3f)', msg.x, msg.header.frame_id, stamp)
"""),
        ("scripts/mover.py", """        rospy.loginfo('Answering a set_target request')
        response = SetTargetResponse()
        response.accepted = True
        return response
""", """        response = SetTargetResponse()
        response.accepted = request.target.x >= 0.0
        rospy.loginfo('set_target: x=%.1f accepted: %s', request.target.x, response.accepted)
        return response
"""),
        ("scripts/mover.py", """        rospy.loginfo('Executing an approach goal')
        server = self.approach_action_server
        rate = rospy.Rate(10)
        for _ in range(3):
            if server.is_preempt_requested() or rospy.is_shutdown():
                server.set_preempted()
                return
            server.publish_feedback(ApproachFeedback())
            rate.sleep()
        server.set_succeeded(ApproachResult())
""", """        rospy.loginfo('approaching to %.1f m', goal.distance)
        server = self.approach_action_server
        rate = rospy.Rate(10)
        remaining = 3.0
        while remaining > goal.distance:
            if server.is_preempt_requested() or rospy.is_shutdown():
                server.set_preempted()
                return
            remaining -= 0.5
            server.publish_feedback(ApproachFeedback(remaining=remaining))
            rate.sleep()
        server.set_succeeded(ApproachResult(reached=True))
"""),
    ],
}

# (sender, receiver, what the sender prints, what the receiver prints), each node's lines in order.
EXCHANGES = {
    "bringup": ("talker", "listener", [r"talker says hello \d+ after [\d.]+ s at 1\.5 Hz"],
                [r"listener heard hello \d+ \(\d+ so far\)"]),
    "tracker": ("detector", "mover",
                [r"detector published target \d+ at x=[\d.]+", r"set_target accepted: True",
                 r"approach: [\d.]+ m to go", r"approach done, reached: True"],
                [r"mover got target at x=[\d.]+ in map \(stamped [\d.]+\)", r"set_target: x=[\d.]+ accepted: True",
                 r"approaching to 1\.5 m"]),
}


def write_user_code(project: Path, name: str) -> list[tuple[str, list[str]]]:
    """The user's code in the generated package at `project`; returns (file, the user's lines)."""
    package = EXAMPLES[name]["package_name"]
    written = []
    for path, starter, mine in USER_CODE[name]:
        written.append((f"{package}/{path}", replace_text(project / package / path, starter, mine)))
    return written
