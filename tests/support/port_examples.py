"""The seed's two examples as a ROS 1 user writes them, for the port's tests.

ROS Node Automator's two examples, in docs/examples: the target tracking system
(`tracker_ros1`: a detector and a mover exchanging their own message, service and action)
and the talker and listener started by one launch file (`bringup_ros1`, with a parameter).
Both are generated as catkin packages, once with their nodes in Python and once in C++, and
their callbacks filled in the way ROS 1 code is written: rospy and roscpp logging with
format arguments, time stamps and their arithmetic, publishing from a timer and from a
callback, a parameter read, a service call, an action goal with feedback. Each edit fails
loudly when the starter it is anchored to changes. The tiers run both on ROS 1 and the
ported Python nodes on ROS 2; the ported C++ nodes run against a real rclcpp in the private
review, outside CI.

`EXCHANGES` is what each node prints when the nodes really talk: the same lines before
and after the port.
"""

from __future__ import annotations

from pathlib import Path

from .generation import example
from .template_repo import replace_text


def variant(name: str, language: str, suffix: str = "") -> dict:
    """The example's answers with every node in `language`, the package's name with `suffix`."""
    answers = example(name)
    answers["nodes"] = [{**node, "language": language} for node in answers["nodes"]]
    answers["package_name"] += suffix
    return answers


EXAMPLES = {"bringup": variant("bringup_ros1", "python"), "tracker": variant("tracker_ros1", "python")}
# The same with every node in C++ (packages of their own names, for one catkin workspace): built
# and run on ROS 1 and ported in the tiers, which hold the ported code to the ROS 2 package's
# ament_cpplint and ament_uncrustify; its ROS 2 build and run are the private rclcpp review's.
CPP_EXAMPLES = {"bringup": variant("bringup_ros1", "cpp", "_cpp"), "tracker": variant("tracker_ros1", "cpp", "_cpp")}

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
        age = (rospy.Time.now() - msg.header.stamp).to_sec()
        rospy.loginfo('mover got target at x=%.1f in %s (stamped %.3f, %.3f s ago)',
                      msg.x, msg.header.frame_id, stamp, age)
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

# The same code in C++, as roscpp users write it.
CPP_USER_CODE = {
    "bringup": [
        ("src/talker.cpp", """    ROS_INFO_STREAM("rate: " << rate_);
  }
""", """    ROS_INFO_STREAM("rate: " << rate_);
    started_ = ros::Time::now();
    period_ = 1.0 / rate_;
  }
"""),
        ("src/talker.cpp", """    String msg;
    msg.data = "Hello World: " + std::to_string(count_);
    ROS_INFO_THROTTLE(
      1.0, "Publishing: \\"%s\\"",
      msg.data.c_str());
    chatter_publisher_.publish(msg);
    ++count_;
  }

private:
  std::size_t count_ = 0;
""", """    String msg;
    msg.data = "hello " + std::to_string(count_);
    double elapsed = (ros::Time::now() - started_).toSec();
    ROS_INFO("talker says %s after %.1f s at %.1f Hz", msg.data.c_str(), elapsed, rate_);
    chatter_publisher_.publish(msg);
    ++count_;
    ROS_DEBUG_THROTTLE(10.0, "period %.2f s", period_);
  }

private:
  std::size_t count_ = 0;
  ros::Time started_;
  double period_ = 0.0;
"""),
        ("src/listener.cpp", """    ROS_INFO(
      "I heard: \\"%s\\"",
      msg->data.c_str());
  }
""", """    ++heard_;
    ROS_INFO("listener heard %s (%zu so far)", msg->data.c_str(), heard_);
    if (!ros::ok()) {
      ROS_WARN("heard while shutting down");
    }
  }

private:
  std::size_t heard_ = 0;
"""),
    ],
    "tracker": [
        ("src/detector.cpp", """    Target msg;
    target_publisher_.publish(msg);
    ++count_;
    if (set_target_client_.exists()) {
      call_set_target(SetTarget::Request());
    }
    if (!approach_goal_active_) {
      if (approach_action_client_.isServerConnected()) {
        send_approach_goal(ApproachGoal());
      }
    }
""", """    Target msg;
    msg.header.stamp = ros::Time::now();
    msg.header.frame_id = "map";
    msg.x = 1.0 + count_;
    msg.y = 2.0;
    target_publisher_.publish(msg);
    ROS_INFO("detector published target %zu at x=%.1f", count_, msg.x);
    ++count_;
    if (set_target_client_.exists()) {
      SetTarget::Request request;
      request.target = msg;
      call_set_target(request);
    }
    if (!approach_goal_active_ && approach_action_client_.isServerConnected()) {
      ApproachGoal goal;
      goal.distance = 1.5;
      send_approach_goal(goal);
    }
"""),
        ("src/detector.cpp", """    (void)response;
    ROS_INFO("set_target answered");
""", """    ROS_INFO("set_target accepted: %s", response.accepted ? "True" : "False");
"""),
        ("src/detector.cpp", """    (void)feedback;
    ROS_INFO("Feedback on the approach goal");
""", """    ROS_INFO("approach: %.1f m to go", feedback->remaining);
"""),
        ("src/detector.cpp", """    (void)result;
    if (state == actionlib::SimpleClientGoalState::SUCCEEDED) {
      ROS_INFO("The approach goal succeeded");
""", """    if (state == actionlib::SimpleClientGoalState::SUCCEEDED) {
      ROS_INFO("approach done, reached: %s", result->reached ? "True" : "False");
"""),
        ("src/mover.cpp", """    (void)msg;
    ROS_INFO("Received a message on target");
""", """    double stamp = msg->header.stamp.toSec();
    double age = (ros::Time::now() - msg->header.stamp).toSec();
    ROS_INFO(
      "mover got target at x=%.1f in %s (stamped %.3f, %.3f s ago)",
      msg->x, msg->header.frame_id.c_str(), stamp, age);
"""),
        ("src/mover.cpp", """    (void)request;
    ROS_INFO("Answering a set_target request");
    response.accepted = true;
    return true;
""", """    response.accepted = request.target.x >= 0.0;
    ROS_INFO("set_target: x=%.1f accepted: %s", request.target.x, response.accepted ? "True" : "False");
    return true;
"""),
        ("src/mover.cpp", """    (void)goal;
    ROS_INFO("Executing an approach goal");
    auto & server = approach_action_server_;
    ros::Rate rate(10.0);
    for (int step = 0; step < 3; ++step) {
      if (server.isPreemptRequested() || !ros::ok()) {
        server.setPreempted();
        return;
      }
      server.publishFeedback(ApproachFeedback());
      rate.sleep();
    }
    server.setSucceeded(ApproachResult());
""", """    ROS_INFO("approaching to %.1f m", goal->distance);
    auto & server = approach_action_server_;
    ros::Rate rate(10.0);
    double remaining = 3.0;
    while (remaining > goal->distance) {
      if (server.isPreemptRequested() || !ros::ok()) {
        server.setPreempted();
        return;
      }
      remaining -= 0.5;
      ApproachFeedback feedback;
      feedback.remaining = remaining;
      server.publishFeedback(feedback);
      rate.sleep();
    }
    ApproachResult result;
    result.reached = true;
    server.setSucceeded(result);
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
                [r"mover got target at x=[\d.]+ in map \(stamped [\d.]+, [\d.]+ s ago\)",
                 r"set_target: x=[\d.]+ accepted: True",
                 r"approaching to 1\.5 m"]),
}


def write_user_code(project: Path, name: str, language: str = "python") -> list[tuple[str, list[str]]]:
    """The user's code in the generated package at `project`; returns (file, the user's lines)."""
    package = (EXAMPLES if language == "python" else CPP_EXAMPLES)[name]["package_name"]
    written = []
    for path, starter, mine in (USER_CODE if language == "python" else CPP_USER_CODE)[name]:
        written.append((f"{package}/{path}", replace_text(project / package / path, starter, mine)))
    return written
