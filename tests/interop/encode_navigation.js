// A navigation CSV (time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad; times are the autopilot's boot
// seconds) sent as an ArduSub autopilot would send it, encoded by node-mavlink: per row an ATTITUDE,
// LOCAL_POSITION_NED, GLOBAL_POSITION_INT (relative_alt = -depth) and SCALED_PRESSURE2 (sea water),
// a HEARTBEAT every tenth row, after one ground station HEARTBEAT (system 255).
//
//   node encode_navigation.js NAV.csv --version 1|2 --tlog OUT [--epoch-us N] [--without local,global,pressure]
//       [--lat-lon LAT,LON]  (GLOBAL_POSITION_INT's lat, lon: that place, degrees; default 0, 0: none)
//       writes a telemetry log: before each frame its reception time, a big-endian uint64 of µs
//       (epoch + boot time + 20 ms, + 0..30 ms of jitter after the first row)
//   node encode_navigation.js NAV.csv --version 1|2 --udp HOST:PORT
//       sends each row's frames as one datagram, in real time (the rows' time differences)
//   node encode_navigation.js NAV.csv --version 1|2 --serve PORT
//       a BlueOS "UDP Server" MAVLink endpoint on 127.0.0.1:PORT: sends nothing until a client's
//       datagram parses (node-mavlink's splitter and parser) as a HEARTBEAT; prints a JSON line per
//       HEARTBEAT heard ({sysid, compid, type, autopilot}); sends the rows, in real time, to every
//       client so heard; exits 0 after the rows, 1 when no HEARTBEAT came in 10 s
'use strict'
const fs = require('fs')
const dgram = require('dgram')
const { MavLinkProtocolV1, MavLinkProtocolV2, minimal, common } = require('node-mavlink')

const args = process.argv.slice(2)
const option = (name, fallback) => {
  const at = args.indexOf(name)
  return at >= 0 ? args[at + 1] : fallback
}
const rows = fs.readFileSync(args[0], 'utf8').trim().split('\n').slice(1).map(line => line.split(',').map(Number))
const Protocol = option('--version', '2') === '1' ? MavLinkProtocolV1 : MavLinkProtocolV2
const without = option('--without', '').split(',')
const [latDeg, lonDeg] = option('--lat-lon', '0,0').split(',').map(Number)
const vehicle = new Protocol(1, 1)
const groundStation = new Protocol(255, 190)
const sequences = new Map()  // per sender
const frame = (protocol, message) => {
  const sequence = sequences.get(protocol) || 0
  sequences.set(protocol, (sequence + 1) % 256)
  return protocol.serialize(message, sequence)
}

function heartbeat(type, autopilot) {
  const m = new minimal.Heartbeat()
  m.type = type
  m.autopilot = autopilot
  m.baseMode = 81
  m.systemStatus = 4
  m.mavlinkVersion = 3
  return m
}

function rowFrames([t, x, y, z, roll, pitch, yaw], index) {
  const timeBootMs = Math.round(t * 1000)
  const frames = []
  if (index === 0) frames.push(frame(groundStation, heartbeat(6, 8)))
  if (index % 10 === 0) frames.push(frame(vehicle, heartbeat(12, 3)))
  const attitude = new common.Attitude()
  Object.assign(attitude, { timeBootMs, roll, pitch, yaw })
  frames.push(frame(vehicle, attitude))
  if (!without.includes('local')) {
    const local = new common.LocalPositionNed()
    Object.assign(local, { timeBootMs, x, y, z })
    frames.push(frame(vehicle, local))
  }
  if (!without.includes('global')) {
    const global = new common.GlobalPositionInt()
    Object.assign(global, { timeBootMs, relativeAlt: Math.round(-z * 1000), hdg: 65535,
      lat: Math.round(latDeg * 1e7), lon: Math.round(lonDeg * 1e7) })
    frames.push(frame(vehicle, global))
  }
  if (!without.includes('pressure')) {
    const pressure = new common.ScaledPressure2()
    Object.assign(pressure, { timeBootMs, pressAbs: (101325 + 1025 * 9.80665 * z) / 100, temperature: 1500 })
    frames.push(frame(vehicle, pressure))
  }
  return frames
}

const tlog = option('--tlog')
if (tlog) {
  const epochUs = BigInt(option('--epoch-us', '1723630500000000'))
  const records = []
  rows.forEach((row, index) => {
    const jitterUs = index === 0 ? 0 : ((index * 7) % 4) * 10000  // the first row is the least delayed
    const received = epochUs + BigInt(Math.round(row[0] * 1e6) + 20000 + jitterUs)
    for (const f of rowFrames(row, index)) {
      const stamp = Buffer.alloc(8)
      stamp.writeBigUInt64BE(received)
      records.push(stamp, f)
    }
  })
  fs.writeFileSync(tlog, Buffer.concat(records))
} else if (option('--serve')) {
  const { MavLinkPacketSplitter, MavLinkPacketParser } = require('node-mavlink')
  const { PassThrough } = require('stream')
  const socket = dgram.createSocket('udp4')
  const clients = new Map()  // "address:port" → {address, port}
  const timeout = setTimeout(() => { console.error('no HEARTBEAT in 10 s'); process.exit(1) }, 10000)
  let started = false
  const sendRows = () => {
    const start = Date.now()
    let index = 0
    const next = () => {
      if (index === rows.length) {
        socket.close()
        return
      }
      const datagram = Buffer.concat(rowFrames(rows[index], index))
      index += 1
      for (const client of clients.values()) socket.send(datagram, client.port, client.address)
      if (index < rows.length) setTimeout(next, Math.max(0, start + (rows[index][0] - rows[0][0]) * 1000 - Date.now()))
      else setTimeout(next, 50)
    }
    next()
  }
  socket.on('message', (datagram, from) => {
    const input = new PassThrough()
    input.pipe(new MavLinkPacketSplitter()).pipe(new MavLinkPacketParser()).on('data', packet => {
      if (packet.header.msgid !== minimal.Heartbeat.MSG_ID) return
      const beat = packet.protocol.data(packet.payload, minimal.Heartbeat)
      process.stdout.write(JSON.stringify({ sysid: packet.header.sysid, compid: packet.header.compid, type: beat.type,
        autopilot: beat.autopilot }) + '\n')
      clients.set(`${from.address}:${from.port}`, { address: from.address, port: from.port })
      if (!started) {
        started = true
        clearTimeout(timeout)
        sendRows()
      }
    })
    input.end(datagram)
  })
  socket.bind(Number(option('--serve')), '127.0.0.1')
} else {
  const [host, port] = option('--udp').split(':')
  const socket = dgram.createSocket('udp4')
  const start = Date.now()
  let index = 0
  const next = () => {
    if (index === rows.length) return socket.close()
    const datagram = Buffer.concat(rowFrames(rows[index], index))
    index += 1
    socket.send(datagram, Number(port), host, error => {
      if (error) throw error
      if (index < rows.length) setTimeout(next, Math.max(0, start + (rows[index][0] - rows[0][0]) * 1000 - Date.now()))
      else next()
    })
  }
  next()
}
