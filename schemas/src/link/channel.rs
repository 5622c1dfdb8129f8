//! [`Link`]: one end of the coupler <-> participant channel pair over iceoryx2 shared memory.
//!
//! Each direction is a publish–subscribe service of `[u8]` (a bincode message per sample) plus an
//! event service whose notification wakes the receiver, so nobody busy-polls. Waits are timed
//! (at most [`MAX_WAIT`]) and a caller-supplied liveness check runs between them, so a dead peer
//! is reported instead of waited on forever.

use super::codec::{decode_exact, encode_into_uninit, encoded_len};
use super::handshake::Hello;
use super::iceoryx_config::{link_config, quiet_iceoryx_logs, INITIAL_MAX_SLICE_LEN, SUBSCRIBER_BUFFER};
use super::liveness::process_alive;
use super::names::{ServiceNames, Side};
use super::LinkError;
use iceoryx2::port::listener::{Listener, ListenerWaitError};
use iceoryx2::port::notifier::Notifier;
use iceoryx2::port::publisher::Publisher;
use iceoryx2::port::subscriber::Subscriber;
use iceoryx2::port::update_connections::UpdateConnections;
use iceoryx2::port::{BackpressureAction, BackpressureInfo, SendError};
use iceoryx2::prelude::*;
use iceoryx2::service::port_factory::{event, publish_subscribe};
use std::fmt::Debug;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The iceoryx2 service flavour: inter-process, ports usable from any thread (`Link: Send + Sync`).
type Ipc = ipc_threadsafe::Service;

/// Longest single wait on an event listener: `alive` is checked at least this often.
pub const MAX_WAIT: Duration = Duration::from_millis(100);

/// Longest pause between two looks at the peer's ports in [`Link::wait_for_peer`].
const PEER_POLL_MAX: Duration = Duration::from_millis(20);

/// One end of the coupler <-> participant link (see the module docs).
pub struct Link {
    side: Side,
    names: ServiceNames,
    /// Set once the hellos were exchanged; `send` refuses to run before.
    connected: AtomicBool,
    /// Pid of the peer process once known (0 = not yet); read by the publisher's backpressure handler.
    peer_pid: Arc<AtomicU32>,
    // Ports are declared before their services and the node, so they are dropped first.
    publisher: Publisher<Ipc, [u8], ()>,
    subscriber: Subscriber<Ipc, [u8], ()>,
    notifier: Notifier<Ipc>,
    listener: Listener<Ipc>,
    outgoing: publish_subscribe::PortFactory<Ipc, [u8], ()>,
    incoming: publish_subscribe::PortFactory<Ipc, [u8], ()>,
    outgoing_wake: event::PortFactory<Ipc>,
    incoming_wake: event::PortFactory<Ipc>,
    _node: Node<Ipc>,
}

impl Link {
    /// Opens this side of the coupler<->participant channel pair. Services carry the run id and
    /// participant name: `tsunami/{run_id}/{participant}/down` (coupler -> participant), `.../up`,
    /// and `.../down/wake`, `.../up/wake` for wake-ups. Creating the node first removes the shared
    /// memory of dead (e.g. SIGKILLed) processes. The first call limits iceoryx2's console log to
    /// errors unless the environment variable `IOX2_LOG_LEVEL` is set.
    pub fn open(run_id: &str, participant: &str, side: Side) -> Result<Link, LinkError> {
        let names = ServiceNames::new(run_id, participant)?;
        quiet_iceoryx_logs();
        let config = link_config()?;
        let node = NodeBuilder::new()
            .config(&config)
            .signal_handling_mode(SignalHandlingMode::Disabled)
            .create::<Ipc>()
            .map_err(|e| LinkError::Iceoryx(format!("cannot create the iceoryx2 node: {e:?}")))?;
        let (out_name, in_name, out_wake_name, in_wake_name) = names.for_side(side);
        let outgoing = open_stream(&node, out_name)?;
        let incoming = open_stream(&node, in_name)?;
        let outgoing_wake = open_wake(&node, out_wake_name)?;
        let incoming_wake = open_wake(&node, in_wake_name)?;

        let subscriber = incoming
            .subscriber_builder()
            .buffer_size(SUBSCRIBER_BUFFER)
            .create()
            .map_err(|e| port_error("subscriber", in_name, e))?;
        let listener = incoming_wake
            .listener_builder()
            .create()
            .map_err(|e| port_error("listener", in_wake_name, e))?;
        let peer_pid = Arc::new(AtomicU32::new(0));
        let handler_pid = Arc::clone(&peer_pid);
        let publisher = outgoing
            .publisher_builder()
            .initial_max_slice_len(INITIAL_MAX_SLICE_LEN)
            .allocation_strategy(AllocationStrategy::PowerOfTwo)
            .max_loaned_samples(1)
            .backpressure_strategy(BackpressureStrategy::RetryUntilDelivered)
            .set_backpressure_handler(move |info: &BackpressureInfo| full_buffer_action(&handler_pid, info))
            .create()
            .map_err(|e| port_error("publisher", out_name, e))?;
        let notifier = outgoing_wake
            .notifier_builder()
            .create()
            .map_err(|e| port_error("notifier", out_wake_name, e))?;

        Ok(Link {
            side,
            names,
            connected: AtomicBool::new(false),
            peer_pid,
            publisher,
            subscriber,
            notifier,
            listener,
            outgoing,
            incoming,
            outgoing_wake,
            incoming_wake,
            _node: node,
        })
    }

    /// Which end of the link this is.
    pub fn side(&self) -> Side {
        self.side
    }

    /// The service names of this link.
    pub fn service_names(&self) -> &ServiceNames {
        &self.names
    }

    /// Pid of the peer process, known after [`Link::wait_for_peer`] succeeded.
    pub fn peer_pid(&self) -> Option<u32> {
        match self.peer_pid.load(Ordering::Relaxed) {
            0 => None,
            pid => Some(pid),
        }
    }

    /// Idle-waits until the peer's ports are connected (so nothing sent is lost), checking `alive`
    /// at least every 100 ms; `Err(PeerGone(msg))` as soon as `alive` returns `Err(msg)`;
    /// `Err(Timeout)` at `deadline`. Once the peer's ports exist, both sides attach their subscriber
    /// and exchange a hello (protocol version, side, pid) that this call consumes. Calling it again
    /// after success returns at once.
    pub fn wait_for_peer(
        &self,
        deadline: Instant,
        alive: &mut dyn FnMut() -> Result<(), String>,
    ) -> Result<(), LinkError> {
        if self.connected.load(Ordering::Acquire) {
            return Ok(());
        }
        let mut pause = Duration::from_micros(250);
        while !self.peer_ports_exist() {
            alive().map_err(LinkError::PeerGone)?;
            let remaining = deadline.saturating_duration_since(Instant::now());
            if remaining.is_zero() {
                return Err(LinkError::Timeout);
            }
            std::thread::sleep(pause.min(remaining));
            pause = (pause * 2).min(PEER_POLL_MAX);
        }
        // Attach our subscriber to the peer's publisher before saying hello: a publisher drops
        // samples for a subscriber that never attached once that subscriber's buffer is full.
        self.subscriber.update_connections().map_err(|e| {
            LinkError::Iceoryx(format!(
                "cannot attach to the peer's publisher on \"{}\": {e:?}",
                self.incoming.name()
            ))
        })?;
        self.send_now(&Hello::new(self.side))?;
        let hello: Hello = self.recv(Some(deadline), alive)?;
        self.peer_pid.store(hello.accept(self.side)?, Ordering::Relaxed);
        self.connected.store(true, Ordering::Release);
        Ok(())
    }

    /// Encodes `msg` with bincode 2 ([`super::bincode_config`]) straight into a loaned shared-memory
    /// sample, sends it and wakes the peer. Lock-step delivery: nothing is dropped; on a full peer
    /// buffer (more than [`SUBSCRIBER_BUFFER`] unread messages) it waits (iceoryx2 yields, then
    /// sleeps) until the peer takes one, or fails with `PeerGone` once the peer process is dead.
    /// `Err(NotConnected)` before [`Link::wait_for_peer`] succeeded. Returns the encoded size in bytes.
    pub fn send<T: bincode::Encode>(&self, msg: &T) -> Result<usize, LinkError> {
        if !self.connected.load(Ordering::Acquire) {
            return Err(LinkError::NotConnected(format!(
                "call wait_for_peer before sending on \"{}\"",
                self.out_name()
            )));
        }
        self.send_now(msg)
    }

    /// [`Link::send`] without the check that the hellos were exchanged.
    fn send_now<T: bincode::Encode>(&self, msg: &T) -> Result<usize, LinkError> {
        let len = encoded_len(msg)?;
        let out_name = self.out_name();
        let mut sample = self.publisher.loan_slice_uninit(len).map_err(|e| {
            LinkError::Iceoryx(format!(
                "cannot get {len} bytes of shared memory on \"{out_name}\": {e:?}"
            ))
        })?;
        encode_into_uninit(msg, sample.payload_mut())?;
        // SAFETY: `encode_into_uninit` returned Ok, so it wrote all `len` bytes of the payload.
        let sample = unsafe { sample.assume_init() };
        let receivers = match sample.send() {
            Ok(receivers) => receivers,
            Err(SendError::UnableToDeliver) => {
                return Err(LinkError::PeerGone(format!(
                    "peer process {} died before taking the message on \"{out_name}\"",
                    self.peer_pid.load(Ordering::Relaxed)
                )))
            }
            Err(e) => {
                return Err(LinkError::Iceoryx(format!(
                    "cannot send on \"{out_name}\": {e:?}"
                )))
            }
        };
        if receivers == 0 {
            return Err(LinkError::PeerGone(format!(
                "nobody receives on \"{out_name}\": the peer has exited"
            )));
        }
        self.notifier.notify().map_err(|e| {
            LinkError::Iceoryx(format!(
                "cannot wake the peer on \"{}\": {e:?}",
                self.outgoing_wake.name()
            ))
        })?;
        Ok(len)
    }

    /// Idle-waits (event-listener waits of at most 100 ms, never busy polling) for the next message,
    /// checking `alive` between waits, and decodes it straight from the shared-memory sample.
    /// `deadline: None` waits forever (but still checks `alive`). `alive` runs after every wait that
    /// brought no message, so a dead peer is reported within about 100 ms; a message the peer sent
    /// just before it exited is still returned.
    pub fn recv<T: bincode::Decode<()>>(
        &self,
        deadline: Option<Instant>,
        alive: &mut dyn FnMut() -> Result<(), String>,
    ) -> Result<T, LinkError> {
        loop {
            if let Some(msg) = self.try_recv()? {
                return Ok(msg);
            }
            let wait = match deadline {
                None => MAX_WAIT,
                Some(deadline) => {
                    let remaining = deadline.saturating_duration_since(Instant::now());
                    if remaining.is_zero() {
                        return Err(LinkError::Timeout);
                    }
                    remaining.min(MAX_WAIT)
                }
            };
            match self.listener.timed_wait(|_| {}, wait) {
                Ok(_) | Err(ListenerWaitError::InterruptSignal) => {}
                Err(e) => {
                    return Err(LinkError::Iceoryx(format!(
                        "cannot wait for wake-ups on \"{}\": {e:?}",
                        self.incoming_wake.name()
                    )))
                }
            }
            if let Some(msg) = self.try_recv()? {
                return Ok(msg);
            }
            if let Err(why) = alive() {
                // The peer may have sent a last message between our look and its exit.
                return self.try_recv()?.ok_or(LinkError::PeerGone(why));
            }
        }
    }

    /// Takes the next message if one is waiting, without blocking.
    pub fn try_recv<T: bincode::Decode<()>>(&self) -> Result<Option<T>, LinkError> {
        match self.subscriber.receive() {
            Ok(Some(sample)) => decode_exact(sample.payload()).map(Some),
            Ok(None) => Ok(None),
            Err(e) => Err(LinkError::Iceoryx(format!(
                "cannot receive on \"{}\": {e:?}",
                self.incoming.name()
            ))),
        }
    }

    /// Name of the service this side publishes on.
    fn out_name(&self) -> &str {
        self.names.for_side(self.side).0
    }

    /// True when the peer's subscriber, publisher, listener and notifier all exist.
    fn peer_ports_exist(&self) -> bool {
        self.outgoing.dynamic_config().number_of_subscribers() > 0
            && self.incoming.dynamic_config().number_of_publishers() > 0
            && self.outgoing_wake.dynamic_config().number_of_listeners() > 0
            && self.incoming_wake.dynamic_config().number_of_notifiers() > 0
    }
}

/// What the publisher does while the peer's buffer is full: keep retrying (iceoryx2 sleeps between
/// tries) unless the peer process is known and dead.
fn full_buffer_action(peer_pid: &AtomicU32, _info: &BackpressureInfo) -> BackpressureAction {
    match peer_pid.load(Ordering::Relaxed) {
        0 => BackpressureAction::Retry,
        pid if process_alive(pid).is_ok() => BackpressureAction::Retry,
        _ => BackpressureAction::DiscardDataAndFail,
    }
}

fn open_stream(
    node: &Node<Ipc>,
    name: &str,
) -> Result<publish_subscribe::PortFactory<Ipc, [u8], ()>, LinkError> {
    node.service_builder(&service_name(name)?)
        .publish_subscribe::<[u8]>()
        .open_or_create()
        .map_err(|e| LinkError::Iceoryx(format!("cannot open the message service \"{name}\": {e:?}")))
}

fn open_wake(node: &Node<Ipc>, name: &str) -> Result<event::PortFactory<Ipc>, LinkError> {
    node.service_builder(&service_name(name)?)
        .event()
        .open_or_create()
        .map_err(|e| LinkError::Iceoryx(format!("cannot open the wake-up service \"{name}\": {e:?}")))
}

fn service_name(name: &str) -> Result<ServiceName, LinkError> {
    ServiceName::new(name).map_err(|e| LinkError::InvalidName(format!("\"{name}\": {e:?}")))
}

fn port_error(port: &str, service: &str, e: impl Debug) -> LinkError {
    LinkError::Iceoryx(format!(
        "cannot create the {port} on \"{service}\": {e:?} (is another process already running this \
         side of the same run id and participant?)"
    ))
}
