// MAVLink frames in a file (sonarmap's encoder wrote them) parsed by node-mavlink's splitter and
// parser, one JSON line per frame: its header and its fields by their names in the XML
// definitions (uint64 fields as decimal strings); then a line of the splitter's counts.
//
//   node parse_frames.js FRAMES.bin
'use strict'
const fs = require('fs')
const { Readable } = require('stream')
const { MavLinkPacketSplitter, MavLinkPacketParser, minimal, common, ardupilotmega } = require('node-mavlink')

const registry = { ...minimal.REGISTRY, ...common.REGISTRY, ...ardupilotmega.REGISTRY }
const splitter = new MavLinkPacketSplitter()
const lines = []
Readable.from([fs.readFileSync(process.argv[2])])
  .pipe(splitter)
  .pipe(new MavLinkPacketParser())
  .on('data', packet => {
    const { header } = packet
    const Message = registry[header.msgid]
    const data = packet.protocol.data(packet.payload, Message)
    const fields = {}
    for (const field of Message.FIELDS) {
      const value = data[field.name]
      fields[field.source] = typeof value === 'bigint' ? value.toString() : value
    }
    lines.push(JSON.stringify({
      magic: packet.buffer[0], seq: header.seq, sysid: header.sysid, compid: header.compid, msgid: header.msgid,
      payloadLength: header.payloadLength, name: Message.MSG_NAME, fields,
    }))
  })
  .on('end', () => {
    lines.push(JSON.stringify({
      summary: true, valid: splitter.validPackages, invalid: splitter.invalidPackages, unknown: splitter.unknownPackagesCount,
    }))
    process.stdout.write(lines.join('\n') + '\n')
  })
