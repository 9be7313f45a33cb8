"""The one table of what porting to ROS 2 rewrites, and of what it leaves marked.

Each rule is one ROS 1 form and the ROS 2 form it becomes. A rewriter (rna.port.python,
rna.port.cpp, rna.port.build) names the rule of each rewrite it makes, so that the
update's summary lists it; a rule marked `todo` rewrites nothing: the line stays as it was
under a `TODO(port): <ros2>` comment, and is counted. The base-class API (rna.port.api)
adds its own rules, made from its table. The docs show this table (docs/hooks/reference.py).
"""

from __future__ import annotations

from . import api
from .rule import Rule

PYTHON = (
    Rule("py.log", "Python", "rospy.loginfo(fmt, *args) (logdebug, logwarn, logerr, logfatal)",
         "self.get_logger().info(f'...') (debug, warning, error, fatal)",
         "the arguments formatted into the message: an f-string where the format has %s, %r and %f only; "
         "outside the node's class: get_logger('<node>') from rclpy.logging"),
    Rule("py.log_throttle", "Python", "rospy.loginfo_throttle(period, msg)",
         "self.get_logger().info(msg, throttle_duration_sec=period)"),
    Rule("py.log_throttle_identical", "Python", "rospy.loginfo_throttle_identical(period, msg)",
         "self.get_logger().info(msg, throttle_duration_sec=period)",
         "rclpy throttles every message, not only repeated ones"),
    Rule("py.log_once", "Python", "rospy.loginfo_once(msg)", "self.get_logger().info(msg, once=True)"),
    Rule("py.now", "Python", "rospy.Time.now(), rospy.get_rostime()", "self.get_clock().now()",
         "with .to_msg() where it fills a message's stamp; outside the node's class: Clock().now()"),
    Rule("py.get_time", "Python", "rospy.get_time()", "self.get_clock().now().nanoseconds / 1e9"),
    Rule("py.time", "Python", "rospy.Time(secs, nsecs), rospy.Time.from_sec(secs)",
         "Time(seconds=secs, nanoseconds=nsecs) (rclpy.time)"),
    Rule("py.duration", "Python", "rospy.Duration(secs, nsecs), rospy.Duration.from_sec(secs)",
         "Duration(seconds=secs, nanoseconds=nsecs) (rclpy.duration)"),
    Rule("py.to_sec", "Python", "t.to_sec(), msg.header.stamp.to_sec()",
         "t.nanoseconds / 1e9, Time.from_msg(msg.header.stamp).nanoseconds / 1e9"),
    Rule("py.to_nsec", "Python", "t.to_nsec()", "t.nanoseconds"),
    Rule("py.stamp_fields", "Python", "stamp.secs, stamp.nsecs", "stamp.sec, stamp.nanosec",
         "builtin_interfaces/Time"),
    Rule("py.sleep", "Python", "rospy.sleep(secs)", "time.sleep(secs)"),
    Rule("py.rate", "Python", "rospy.Rate(hz)", "self.create_rate(hz)",
         "its sleep() needs the node's executor turning: in a goal thread, not in a callback"),
    Rule("py.is_shutdown", "Python", "rospy.is_shutdown()", "not self.context.ok()",
         "outside the node's class: not rclpy.ok()"),
    Rule("py.on_shutdown", "Python", "rospy.on_shutdown(callback)", "self.context.on_shutdown(callback)"),
    Rule("py.publisher", "Python", "rospy.Publisher(topic, Type, queue_size=n, latch=True)",
         "self.create_publisher(Type, topic, n), latched: QoSProfile(depth=n, durability=TRANSIENT_LOCAL)"),
    Rule("py.subscriber", "Python", "rospy.Subscriber(topic, Type, callback, queue_size=n)",
         "self.create_subscription(Type, topic, callback, n)"),
    Rule("py.timer", "Python", "rospy.Timer(rospy.Duration(secs), callback)", "self.create_timer(secs, callback)",
         "the callback gets no event in ROS 2"),
    Rule("py.service_proxy", "Python", "rospy.ServiceProxy(name, Type)", "self.create_client(Type, name)"),
    Rule("py.wait_for_service", "Python", "client.wait_for_service(timeout=secs)",
         "client.wait_for_service(timeout_sec=secs)"),
    Rule("py.param", "Python", "rospy.get_param('~name', default), a parameter of the node",
         "self.get_parameter('name').value"),
    Rule("py.srv_types", "Python", "from pkg.srv import FooRequest, FooResponse; FooRequest()",
         "from pkg.srv import Foo; Foo.Request()"),
    Rule("py.action_types", "Python", "from pkg.msg import FooAction, FooGoal, FooResult, FooFeedback; FooGoal()",
         "from pkg.action import Foo; Foo.Goal()"),
    Rule("py.goal_status", "Python", "from actionlib_msgs.msg import GoalStatus; GoalStatus.SUCCEEDED",
         "from action_msgs.msg import GoalStatus; GoalStatus.STATUS_SUCCEEDED",
         "PENDING -> STATUS_ACCEPTED, ACTIVE -> STATUS_EXECUTING, PREEMPTING and RECALLING -> STATUS_CANCELING, "
         "PREEMPTED and RECALLED -> STATUS_CANCELED"),
    Rule("py.wait_for_server", "Python", "action_client.wait_for_server(rospy.Duration(secs))",
         "action_client.wait_for_server(timeout_sec=secs)"),
    Rule("py.imports", "Python", "import rospy, import actionlib, from actionlib import ...",
         "(removed: what they gave is rewritten, or marked)"),
    Rule("py.todo.header_seq", "Python", "header.seq", "std_msgs/Header has no seq in ROS 2: count in a member",
         todo=True),
    Rule("py.todo.param", "Python", "rospy.get_param(name) of a parameter the node does not declare",
         "add it to the node's parameters (copier update), then self.get_parameter('name').value", todo=True),
    Rule("py.todo.global_param", "Python", "rospy.get_param('/name'), rospy.set_param, rospy.has_param",
         "ROS 2 has no parameter server: parameters are a node's (self.get_parameter, self.set_parameters)",
         todo=True),
    Rule("py.todo.service_call", "Python", "proxy(request), rospy.wait_for_service(name)",
         "self.call_<service>(request); the answer comes to on_<service>_response",
         "a blocking call in a callback never returns in ROS 2", todo=True),
    Rule("py.todo.service", "Python", "rospy.Service(name, Type, callback)",
         "self.create_service(Type, name, callback), callback(request, response) returning the response",
         todo=True),
    Rule("py.todo.main", "Python", "rospy.init_node(), rospy.spin(), rospy.signal_shutdown()",
         "main() of the ROS 2 starter creates, spins and shuts down the node", todo=True),
    Rule("py.todo.wait_for_message", "Python", "rospy.wait_for_message(topic, Type)",
         "a subscription, or wait_for_message(Type, self, topic) from rclpy.wait_for_message", todo=True),
    Rule("py.todo.tf", "Python", "import tf", "tf2_ros: Buffer, TransformListener, TransformBroadcaster",
         todo=True),
    Rule("py.todo.dynamic_reconfigure", "Python", "dynamic_reconfigure",
         "ROS 2 parameters: self.add_on_set_parameters_callback()", todo=True),
    Rule("py.todo.callback_args", "Python", "rospy.Subscriber(..., callback_args=x)",
         "a lambda or functools.partial as the callback", todo=True),
    Rule("py.todo.timer_event", "Python", "the event of a timer callback", "self.get_clock().now()",
         "ROS 2 timer callbacks get no event", todo=True),
    Rule("py.todo.call_result", "Python", "the value of self.call_<service>(request)",
         "a future; the answer comes to on_<service>_response", todo=True),
    Rule("py.todo.goal_handling", "Python", "the action server's set_succeeded() before more code, or its other "
         "methods", "goal_handle.succeed() then return the result (rclpy.action)", todo=True),
    Rule("py.todo.other", "Python", "any other use of rospy, actionlib, roslib, rosparam, rosbag",
         "write it with rclpy", todo=True),
)

RULES: tuple[Rule, ...] = PYTHON + api.RULES
BY_KEY = {rule.key: rule for rule in RULES}


def rule(key: str) -> Rule:
    return BY_KEY[key]
