// A Qt Quick scene for the input tests: a MouseArea that turns its rectangle from red to
// green on a click, and a TextInput that shows what is typed. Each reaction is also printed,
// so that a test reads it from the program's output as well as from the screen.
import QtQuick 2.0
import QtQuick.Window 2.0

Window {
    width: 200
    height: 160
    visible: true
    color: "white"

    Rectangle {
        id: button
        property bool clicked: false
        x: 0
        y: 0
        width: 100
        height: 80
        color: clicked ? "#00ff00" : "#ff0000"

        MouseArea {
            anchors.fill: parent
            onClicked: {
                button.clicked = true;
                console.log("clicked " + mouse.x + " " + mouse.y);
            }
        }
    }

    TextInput {
        id: input
        x: 0
        y: 96
        width: 200
        height: 64
        focus: true
        color: "black"
        font.pixelSize: 48
        onTextChanged: console.log("text " + text)
    }
}
