//! The iceoryx2 configuration of the link, set in code (no config file is read, so no warning).

use iceoryx2::prelude::{AllocationStrategy, BackpressureStrategy, Config};

/// Messages a subscriber can hold before its publisher must wait (lock-step needs 1; the rest is slack
/// for a few messages sent in a row).
pub const SUBSCRIBER_BUFFER: usize = 8;

/// Slice length the publisher's shared memory is first sized for; larger messages grow it by powers of two.
pub const INITIAL_MAX_SLICE_LEN: usize = 64 * 1024;

/// One coupler and one participant per service: one publisher, one subscriber, one notifier and one
/// listener, in two nodes. A second process claiming the same side fails instead of cross-talking.
const PORTS_PER_SERVICE: usize = 1;
const NODES_PER_SERVICE: usize = 2;

/// The configuration every node of the link is created with.
pub fn link_config() -> Config {
    let mut config = Config::default();
    // Dead nodes of a SIGKILLed run are removed when a node is created or a service opened (the
    // 0.10 defaults, set explicitly because the link relies on them).
    config.global.node.cleanup_dead_nodes_on_creation = true;
    config.global.node.cleanup_dead_nodes_on_destruction = true;
    config.global.service.cleanup_dead_nodes_on_open = true;

    let ps = &mut config.defaults.publish_subscribe;
    ps.max_publishers = PORTS_PER_SERVICE;
    ps.max_subscribers = PORTS_PER_SERVICE;
    ps.max_nodes = NODES_PER_SERVICE;
    ps.subscriber_max_buffer_size = SUBSCRIBER_BUFFER;
    ps.subscriber_max_borrowed_samples = 1;
    ps.publisher_max_loaned_samples = 1;
    ps.publisher_history_size = 0;
    ps.enable_safe_overflow = false;
    ps.backpressure_strategy = BackpressureStrategy::RetryUntilDelivered;
    ps.publisher_allocation_strategy = AllocationStrategy::PowerOfTwo;

    let ev = &mut config.defaults.event;
    ev.max_listeners = PORTS_PER_SERVICE;
    ev.max_notifiers = PORTS_PER_SERVICE;
    ev.max_nodes = NODES_PER_SERVICE;
    config
}
