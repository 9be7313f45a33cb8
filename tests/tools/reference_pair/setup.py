from setuptools import setup

package_name = 'reference_pair'

setup(
    name=package_name,
    version='0.0.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Ada Lovelace',
    maintainer_email='ada@example.com',
    description="ros2/examples' minimal publisher and subscriber",
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'talker = reference_pair.publisher_member_function:main',
            'listener = reference_pair.subscriber_member_function:main',
        ],
    },
)
